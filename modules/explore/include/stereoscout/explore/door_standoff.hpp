#pragma once
// Door standoff (explore.door_standoff_m): look at a door square on before passing it.
//
// A door sighting (door_sighting.hpp) corrects the pose across a door only from a scan taken
// with the camera at least DoorSighting::kMinAhead_m before the door's line and both jambs
// well inside the image. A door in a corridor's side wall is seen only obliquely until the
// robot turns into it, and by then it is too near; a robot that turned round just past a door
// is nearer still. Over windows of five office seeds, with sighting and axis at 1.4 m, 1 to 10
// doors a run were sighted, most door scans saw no gap or a jamb at the image's edge, and the
// one contact left was met on an approach without a sighting (docs/results.md).
//
// When the plan passes a door (the door axis's passage), the robot first drives to the standoff point on the door's axis, door_standoff_m before its
// middle (a robot that passed the door and now turns round to pass it again, facing away
// from it, drives on to the point rather than turn round nearer the door), then turns in
// place to face along the axis: the turn brings an update (and a scan)
// each degree, and the last ones see the door square on. Then it goes on along the axis. A
// sighting on the way does not end the standoff: one taken obliquely, carried by the odometry
// through the turns of an approach aside of the axis, had drifted 0.13-0.15 m across the door
// by the jambs (office seeds 3 and 6, the first version of this rule; docs/results.md), while
// from the point the robot drives straight in, sighting the door again on the way. The door is
// given up, and the robot goes on as without a standoff, when the grid holds no wall beside it (DoorSighting::in_a_wall: a gap between two
// pieces of furniture is passed without a sighting anyway), when the straight way to the
// point is not clear (the caller checks it), when the robot stands nearer the door than the
// point, facing it, and its camera would stand nearer than kMinAhead_m, or when the approach
// takes longer than kApproachLimit_s or the turn twice the time a half turn needs.
//
// Off by default: over windows of five office seeds it acted at only 13 door passages, because
// most doors failed the wall test (the office's blank walls beside them are not in the grid),
// and it did not lower the contacts (docs/results.md, "a door standoff, tried").
//
// Fixed-size state; steer() allocates nothing.

#include <cstdint>

#include <Eigen/Core>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/explore/door_axis.hpp"
#include "stereoscout/explore/grid_view.hpp"

namespace stereoscout::explore {

struct DoorStandoffCounters {
  std::uint64_t doors = 0;      // doors (gaps in a wall) on the plan, while on
  std::uint64_t stood_off = 0;  // of them: the robot reached the point (or could turn where it stood)
  std::uint64_t sighted = 0;    // of them: a sighting held when the robot faced along the axis
  std::uint64_t not_in_a_wall = 0;  // left: a gap the grid holds no wall beside (no sighting would be taken)
  std::uint64_t too_near = 0;   // given up: found with the robot too near to turn and see it
  std::uint64_t way_shut = 0;   // given up: the straight way to the point not clear
  std::uint64_t timed_out = 0;  // given up: the approach or the turn took too long
};

class DoorStandoff {
 public:
  // The point is reached within this distance of it (at 0.12 m/s a 20 Hz drive tick moves
  // 0.006 m).
  static constexpr double kReached_m = 0.05;
  // Facing along the axis within this angle (the turn's updates come every degree).
  static constexpr double kFacing_rad = 0.03;
  // An approach that takes longer than this is given up: something the grid does not hold
  // keeps the robot from the point, and the stall and stuck rules act on the plan's progress,
  // which the standoff does not make. At 0.12 m/s it covers 2 m with two quarter turns.
  static constexpr double kApproachLimit_s = 30.0;

  explicit DoorStandoff(const ExploreParams& params);

  bool enabled() const { return standoff_m_ > 0.0; }
  void reset();
  // The point `passage`'s standoff drives to.
  Eigen::Vector2d point(const DoorPassage& passage) const;
  // Whether steer() with `passage` needs the grid's answers (it drives to the point, or may
  // begin to: no door yet, or `passage` is another door than the last one's).
  bool wants_grid(const DoorPassage& passage) const;
  // What the caller found in its grid for the door axis's passage.
  struct GridAnswers {
    bool in_a_wall = false;  // DoorSighting::in_a_wall(passage)
    bool way_clear = false;  // the disc can drive straight from the robot to point(passage)
  };
  // Whether the robot, at `pose` with the door axis's `passage` (known or not), stands off for
  // it now: then `command` is the drive command. `sighted` (a sighting of that door is held)
  // is only counted.
  bool steer(const DoorPassage& passage, bool sighted, const GridAnswers& grid, const core::Pose2& pose,
             double time_s, core::DriveCommand& command);
  const DoorStandoffCounters& counters() const { return counters_; }

 private:
  enum class Phase : std::uint8_t { none, approach, face, done };

  void begin(const DoorPassage& passage, bool in_a_wall, const core::Pose2& pose, double time_s);
  void give_up(std::uint64_t& reason);
  double phase_limit_s() const;

  ExploreParams params_;
  double standoff_m_ = 0.0;
  DoorPassage door_;
  Phase phase_ = Phase::none;
  double phase_start_s_ = 0.0;
  DoorStandoffCounters counters_;
};

}  // namespace stereoscout::explore
