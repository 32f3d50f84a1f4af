#pragma once
// Contacts with what the camera did not see. The robot has no bumper, and a surface without
// texture (a blank wall, a plain pillar) gives the dense stereo no disparity: its cells stay
// unknown, and near the robot the planner may cross unknown cells (the camera's blind zone).
// So the robot can drive into it. Like a robot that reads its motor currents, the explorer
// then notices that it is not moving although it commands motion (StallDetector), and marks
// the cells just beyond its rim ahead as occupied for planning (ContactMemory), so the next
// plan leads around them.
//
// StallDetector compares, over windows of stall_window_s, the forward travel commanded with
// the travel the explorer hands it: with stall_from_odometry (the default) the odometry's,
// otherwise the pose estimate's (which follows odometry between updates but is corrected at
// each, and a correction back along the way reads as a stall): stalled when
// less than stall_progress_fraction of it was travelled. A window is judged once it has
// commanded at least stall_min_commanded_m, so a slow command stretches it. Any tick without
// a forward command starts a new window, so turns in place and looks never count.
//
// ContactMemory keeps contact cells in a fixed list. A contact is forgotten after
// contact_hold_s, or as soon as the grid sees its cell free when it had held it unknown or
// occupied at the contact: a person who stood there has walked on. (A cell the grid held free
// at the contact is wrong in the grid, a surface it cannot see: only the time limit ends it.)
// Both rules depend on simulated time and the grid only, so runs stay reproducible.
//
// A contact point within trail_contact_radius_m of the robot's own trail (TrailMemory: where
// its centre was) is not recorded: the robot's disc passed there, so nothing stands there.
// Leaving a room by the door it came in by, a robot that touches a jamb pushes with the
// doorway straight ahead, and a contact cell there would close the door for contact_hold_s.
//
// A stall with a mapped surface (an occupied cell) within contact_explained_margin_m of the
// rim, in front of the robot's middle, is explained by it: the robot met what the grid holds,
// off by the pose error. Its contact points on cells the grid holds free are not recorded:
// only contact_hold_s would end them, and marked ahead of a robot that met a jamb beside it,
// they shut the door it stood in. Those on unknown cells are, as for any stall. A stall
// explains itself so once only: another within contact_repeat_radius_m of where the robot
// stood at an explained one is recorded in full, or a robot whose pose is off would push into
// the same surface stall after stall (office seed 3, the pose 3 m off: every 17 s for 510 s).
//
// The contact cells are where the pose estimate put the rim, so they can close a door the robot
// touched a jamb of (a contact ahead, another backing out): the explorer clears them before it
// concludes that nothing is left or gives the return up (clear()). But a contact made again
// within contact_repeat_radius_m of one cleared before is real: clear() keeps it, or the
// explorer would drive into the same surface after every clear.

#include <cstdint>
#include <memory>

#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/explore/trail_memory.hpp"

namespace stereoscout::explore {

class StallDetector {
 public:
  explicit StallDetector(const core::ExploreConfig& config);

  // Call once per tick before the new command: accounts the command of the previous tick over
  // the time since, and returns true when a window just ended stalled.
  bool stalled(double time_s, const Eigen::Vector2d& position);
  // The forward speed commanded at time_s from `position` (for the next call to stalled()).
  void commanded(double time_s, const Eigen::Vector2d& position, double linear_mps);
  void reset();

 private:
  double window_s_;
  double min_commanded_m_;
  double progress_fraction_;
  bool window_open_ = false;
  double window_start_s_ = 0.0;
  Eigen::Vector2d window_start_position_ = Eigen::Vector2d::Zero();
  double commanded_m_ = 0.0;
  double last_time_s_ = 0.0;
  double last_linear_mps_ = 0.0;
  Eigen::Vector2d last_position_ = Eigen::Vector2d::Zero();
};

class ContactMemory {
 public:
  // max_width x max_height: the largest grid stamp() must copy (allocated here, at start-up).
  ContactMemory(const core::ExploreConfig& config, int max_width, int max_height);

  // Records the cells just beyond the rim of a robot of `radius_m` at `pose`: straight ahead
  // and contact_arc_deg to either side, but those on `trail` and, when a mapped surface explains
  // the stall, those on free cells. `grid`: the grid the robot planned on.
  void record(const GridView& grid, const core::Pose2& pose, double radius_m, double time_s,
              const TrailMemory& trail);
  // Forgets expired and freed contacts, then returns `grid` with the contact cells occupied:
  // a copy in the memory's own buffer, or `grid` itself when there is no contact (or it is
  // larger than the buffer, counted). Valid until the next call.
  GridView stamp(const GridView& grid, double time_s);
  // Forgets every contact but those made again where a cleared one was; returns how many it
  // forgot.
  std::size_t clear();

  std::size_t held() const { return contacts_.size(); }
  std::uint64_t recorded() const { return recorded_; }
  std::uint64_t forgotten_full() const { return forgotten_full_; }  // the list was full
  std::uint64_t freed() const { return freed_; }                    // seen free later
  std::uint64_t expired() const { return expired_; }
  std::uint64_t cleared() const { return cleared_; }
  std::uint64_t repeated() const { return repeated_; }  // contacts made again where one was cleared
  std::uint64_t on_trail() const { return on_trail_; }  // not recorded: the robot had driven there
  std::uint64_t explained() const { return explained_; }  // not recorded: free, beside a mapped surface
  std::uint64_t toward_mapped() const { return toward_mapped_; }  // stalls marked towards a mapped surface
  std::uint64_t grid_too_large() const { return grid_too_large_; }

 private:
  struct Contact {
    Eigen::Vector2d point;
    double time_s = 0.0;
    bool free_at_contact = false;  // the grid held the cell free when the robot touched it
    bool repeated = false;         // near a contact cleared before: not cleared again
  };
  bool keep(const Contact& contact, const GridView& grid, double time_s);
  bool near_a_cleared_contact(const Eigen::Vector2d& point) const;
  bool on_trail(const Eigen::Vector2d& point, const TrailMemory& trail) const;
  bool nearest_mapped_in_front(const GridView& grid, const core::Pose2& pose, double reach_m,
                               Eigen::Vector2d& offset) const;
  bool mapped_stall_here_before(const Eigen::Vector2d& position) const;

  double arc_rad_;
  double hold_s_;
  double repeat_radius_m_;
  double trail_radius_m_;
  double explained_margin_m_;
  double toward_mapped_m_;
  core::FixedVector<Contact> contacts_;
  core::FixedVector<Eigen::Vector2d> cleared_points_;  // the oldest are kept when it is full
  // Where stalls were explained by, or marked towards, a mapped surface; likewise.
  core::FixedVector<Eigen::Vector2d> mapped_stalls_at_;
  std::unique_ptr<std::uint8_t[]> cells_;
  std::size_t cell_capacity_;
  std::uint64_t recorded_ = 0;
  std::uint64_t forgotten_full_ = 0;
  std::uint64_t freed_ = 0;
  std::uint64_t expired_ = 0;
  std::uint64_t cleared_ = 0;
  std::uint64_t repeated_ = 0;
  std::uint64_t on_trail_ = 0;
  std::uint64_t explained_ = 0;
  std::uint64_t toward_mapped_ = 0;
  std::uint64_t grid_too_large_ = 0;
};

}  // namespace stereoscout::explore
