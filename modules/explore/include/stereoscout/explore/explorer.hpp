#pragma once
// The exploration behaviour (paper VI) as one tick function the stack calls every control
// tick: look around 360 degrees (pan unit, or turn in place without one), choose the goal of
// highest value H, plan A* to it, follow the plan; after every observation update rebuild the
// navigation map, check the rest of the plan and replan when it is blocked; no safe plan ->
// another goal; a goal that keeps failing is blacklisted. Optionally (goal_shift_radius_m, off
// by default), a goal whose own cell a later update makes impassable (an obstacle cell within
// the robot's radius of it: a person's trace, a stereo outlier) is not failed for that: the
// plan goes to the nearest passable cell in sight of it. Exploration ends when no goal is
// worth more than min_goal_value or at time_limit_s, then the robot returns to the start if
// configured. With pan_at_goal, neither "no goal" nor "no way back" is concluded before a
// fresh look from where the robot stands (people walking past leave traces that a look
// clears; see the occupancy grid). Neither "no plan" nor "nothing left" is concluded on a
// person's old traces either (trace_forget_after_s): plans cross them until that goal ends
// (trace_memory.hpp); nor on a passage the robot drove through that the grid has closed since
// (trail_length_m): plans follow its own path back (trail_memory.hpp).
//
// Safety, every tick: the emergency stop commands zero velocity in the same call; before any
// forward motion the next stretch of the plan (and the point just ahead of the robot) is
// checked against the cells the current grid holds as occupied, and the robot stops if the
// disc would touch one it does not already touch (optionally keeping fresh_obstacle_margin_m
// more from cells that just turned occupied where the floor was free: trace_memory.hpp).
// With scan_guard_min_points (on by default) it also stands still, without a look,
// while within scan_guard_distance_m along the plan or its heading it would touch that many
// of the obstacles the latest scan saw at the camera's height (a person walking in, whom the
// grid holds only some updates later).
// With door_axis_before_m, it steers along the axis of the door the plan passes next
// (door_axis.hpp). With door_sighting_range_m, it navigates by a pose corrected across that
// door by where the latest scans saw its gap (door_sighting.hpp). With both and
// door_standoff_m, it first looks at a door it has no sighting of square on, from a point on
// its axis (door_standoff.hpp).
// With gaze_ahead_m, the pan unit points the camera along the plan while it drives, at the
// waypoint that far ahead, so that the door of a turn is in view before the turn.
// If facing the plan's next waypoint would clear the way (pure pursuit cut a corner beside an
// obstacle), it turns in place to face it instead. Otherwise, with pan_at_goal, it looks around
// (a standing robot makes no observation update, so nothing would clear a person's trace)
// and carries on to the same goal on a new plan. A robot that commands forward motion but
// does not move has touched something the camera did not see (contact_memory.hpp): it stops,
// the cells just beyond its rim ahead count as occupied for planning, and it replans.
// With recent_obstacle_s, what the recent scans saw at the camera's height, kept in the
// odometry frame, counts as occupied too, for the plans and the safety check alike
// (recent_obstacles.hpp).
//
// All buffers are allocated by the constructor; step() allocates nothing.

#include <cstdint>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/explore/contact_memory.hpp"
#include "stereoscout/explore/door_axis.hpp"
#include "stereoscout/explore/door_sighting.hpp"
#include "stereoscout/explore/door_standoff.hpp"
#include "stereoscout/explore/explore_journal.hpp"
#include "stereoscout/explore/goal_value.hpp"
#include "stereoscout/explore/grid_view.hpp"
#include "stereoscout/explore/navigation_map.hpp"
#include "stereoscout/explore/path_follower.hpp"
#include "stereoscout/explore/path_planner.hpp"
#include "stereoscout/explore/recent_obstacles.hpp"
#include "stereoscout/explore/seen_obstacles.hpp"
#include "stereoscout/explore/shut_gaps.hpp"
#include "stereoscout/explore/trace_memory.hpp"
#include "stereoscout/explore/trail_memory.hpp"

namespace stereoscout::explore {

struct ExploreInput {
  double time_s = 0.0;
  core::Pose2 pose;       // map frame: the ML particle's pose (ground truth in simulation tests)
  core::Pose2 odometry;   // the raw odometry pose now (any fixed frame; seen.odometry's)
  double pan_rad = 0.0;   // current angle of the pan unit
  GridView grid;          // current grid; must stay valid during the call only
  SeenObstacles seen;     // the latest scan's obstacles at camera height (scan_guard_min_points)
  bool grid_updated = false;    // an observation update changed the grid since the last call
  bool emergency_stop = false;  // from the Gpio shim
};

enum class ExploreState : std::uint8_t { look_around, choose_goal, drive, returning, finished };
const char* to_string(ExploreState state);

enum class FinishReason : std::uint8_t { none, explored, time_limit };

struct ExploreOutput {
  core::DriveCommand drive;    // already within the robot's limits
  double pan_target_rad = 0.0;  // where the pan unit should point (0 = forward)
  ExploreState state = ExploreState::look_around;
};

struct ExploreCounters {
  std::uint64_t map_rebuilds = 0;
  std::uint64_t goals_chosen = 0;
  std::uint64_t goals_reached = 0;
  std::uint64_t goals_abandoned = 0;   // value fell below min_goal_value while driving
  std::uint64_t goal_failures = 0;     // no plan, no progress for stuck_timeout_s, or out of time
  std::uint64_t goals_blacklisted = 0;
  std::uint64_t plan_failures = 0;
  std::uint64_t replans = 0;           // plan blocked after an observation update
  std::uint64_t goal_shifts = 0;       // plans to a passable cell near a goal whose own cell became impassable
  std::uint64_t stuck = 0;
  std::uint64_t goal_timeouts = 0;    // pursued longer than goal_time_factor allows
  std::uint64_t net_progress_timeouts = 0;  // no nearer than ever before for net_progress_timeout_s
  std::uint64_t blocked_plan_limits = 0;    // goals failed for plans blocked max_blocked_plans times
  std::uint64_t plan_reversals = 0;         // blocked plans replaced by one leading back (plan_reversal_deg)
  std::uint64_t reversal_limits = 0;        // goals failed for max_plan_reversals of them
  std::uint64_t safety_stops = 0;
  std::uint64_t scan_guard_stops = 0;  // holds for the latest scan's obstacles, the grid clear there (no look)
  std::uint64_t turns_to_face_plan = 0;  // ticks turning to face the plan instead of a safety stop
  std::uint64_t layer_gap_steers = 0;    // ticks steering through the recent obstacle layer's gap
  std::uint64_t stalls = 0;            // forward motion commanded, none made: a contact
  std::uint64_t emergency_stop_ticks = 0;
  std::uint64_t looks = 0;
  std::uint64_t return_failures = 0;  // no way back or no progress on it; given up at goal_failures_before_blacklist
  std::uint64_t looks_before_giving_up = 0;  // no goal, or no way back: one more look first
  std::uint64_t back_offs = 0;       // backed off after a stall, or to see a trace (back_offs_to_see)
  std::uint64_t back_offs_to_see = 0;  // ... a safety stop on a trace where the camera sees no floor
  std::uint64_t back_off_turns = 0;  // ... turning in place first, the way straight back shut
  std::uint64_t contact_clears = 0;  // contacts forgotten (but repeated ones) before concluding "explored" or "no way back"
  std::uint64_t blacklist_releases = 0;  // held blacklistings lifted before concluding "explored" (blacklist_releases)
  std::uint64_t shut_gap_lifts = 0;  // shut gaps lifted before concluding "explored" or "no way back" (shut_gap_hold_s)
  std::uint64_t trace_crossings = 0;   // plans let cross old traces rather than conclude "no plan" or "nothing left"
  std::uint64_t trail_follows = 0;     // plans let follow the robot's own path rather than conclude "explored" or "no way back"
  std::uint64_t traces_confirmed = 0;  // trace cells still occupied after a look: obstacles since
  std::uint64_t plans_kept_for_walkers = 0;  // blocked only by passers-by: kept (wait_for_walkers)
  std::uint64_t walker_waits_ended = 0;      // a goal's walker_wait_per_goal_s used up: replanned as without it
  std::uint64_t plans_switched = 0;          // a fresh plan cheaper by plan_switch_saving_m taken over the kept one
  std::uint64_t walker_holds = 0;            // a kept plan's passer-by near: the robot stood still (walker_hold_s)
  std::uint64_t traces_seen_standing = 0;  // cells seen occupied in view for trace_view_updates: never traces
};

class Explorer {
 public:
  explicit Explorer(const ExploreParams& params);

  ExploreOutput step(const ExploreInput& input);

  ExploreState state() const { return state_; }
  FinishReason finish_reason() const { return finish_reason_; }
  const Goal& goal() const { return goal_; }
  const Plan& plan() const { return plan_; }
  const ExploreCounters& counters() const { return counters_; }
  const NavigationMap& navigation_map() const { return map_; }
  const GoalValue& goal_value() const { return goal_value_; }
  const ContactMemory& contacts() const { return contacts_; }
  const ShutGaps& shut_gaps() const { return gaps_; }
  const RecentObstacles& recent_obstacles() const { return recent_; }
  const DoorSighting& door_sighting() const { return sighting_; }
  const DoorStandoff& door_standoff() const { return standoff_; }
  const ExploreJournal& journal() const { return journal_; }

 private:
  // `input` with the pose the explorer navigates by (door_sighting.hpp): a copy in
  // navigation_input_, or `input` itself.
  const ExploreInput& navigation_input(const ExploreInput& input);
  void start(const ExploreInput& input);
  void rebuild(const ExploreInput& input);
  void rebuild_map(const ExploreInput& input);
  bool clear_contacts(const ExploreInput& input);
  bool release_blacklist(const ExploreInput& input);
  void shut_gap(const ExploreInput& input);
  bool lift_shut_gaps(const ExploreInput& input);
  bool start_crossing_traces(const ExploreInput& input);
  bool start_following_trail(const ExploreInput& input);
  template <typename Changed>
  bool start_last_resort(bool& active, Changed&& changed, ExploreEventKind kind, std::uint64_t& count,
                         const ExploreInput& input);
  void stop_last_resorts(const ExploreInput& input);
  bool blocked_by_passers_by(const ExploreInput& input, const Eigen::Vector2i& cell) const;
  bool may_wait_for_walkers(const ExploreInput& input);
  bool blocked_too_often() const;
  bool leads_back(const core::Pose2& pose) const;
  bool reversed_too_often(const ExploreInput& input);
  void stop_waiting_for_walkers(double time_s);
  void begin_walker_waits();
  void hold_for_walker(const ExploreInput& input, const Eigen::Vector2i& blocked_cell);
  bool plan_to_goal(const ExploreInput& input);
  void check_plan(const ExploreInput& input);
  bool replan(const ExploreInput& input);
  bool switch_to_cheaper_plan(const ExploreInput& input);
  bool narrow_ahead() const;
  void note_plan_length(const ExploreInput& input);
  void begin_pursuit(const ExploreInput& input);
  double remaining_path_m(const Eigen::Vector2d& position) const;
  bool out_of_time(double time_s) const;
  void track_net_progress(double remaining_m, double time_s);
  bool without_net_progress(double time_s) const;
  void choose_goal(const ExploreInput& input);
  void finish_exploring(const ExploreInput& input, FinishReason reason);
  void goal_failed(const ExploreInput& input);
  void begin_look(const ExploreInput& input);
  void finish_look(const ExploreInput& input);
  void look_step(const ExploreInput& input, ExploreOutput& output);
  void drive_step(const ExploreInput& input, ExploreOutput& output);
  // Whether the camera looks along the plan while driving (explore.gaze_ahead_m, with a pan unit).
  bool gazing() const { return params_.explore.gaze_ahead_m > 0.0 && params_.has_pan_unit; }
  // explore.gaze_ahead_m: the pan angle that points the camera at the plan's waypoint that far ahead.
  double gaze_pan_rad(const core::Pose2& pose) const;
  void stop_and_look(const ExploreInput& input, ExploreOutput& output, double turn_rad_s);
  void hold_for_scan(const ExploreInput& input);
  void begin_back_off(const ExploreInput& input, ExploreOutput& output, double distance_m);
  bool back_off_to_see(const ExploreInput& input, ExploreOutput& output);
  bool back_off_blocked(const ExploreInput& input, double heading_rad, double reach_m) const;
  bool straight_move_blocked(const GridView& grid, const ExploreInput& input, const Eigen::Vector2d& direction,
                             double from_m, double to_m, bool scan_too) const;
  double least_back_off_reach_m() const;
  void choose_back_off_heading(const ExploreInput& input);
  bool back_off_step(const ExploreInput& input, ExploreOutput& output);
  enum class Blocked : std::uint8_t { no, by_grid, by_scan };
  Blocked stretch_blocked(const GridView& grid, const ExploreInput& input) const;
  bool turn_to_face_plan(const GridView& grid, const ExploreInput& input, ExploreOutput& output);
  // The door standoff's command in place of `command` while it stands off (door_standoff.hpp).
  void stand_off(const GridView& grid, const ExploreInput& input, core::DriveCommand& command);
  // explore.layer_gap_reach_m: steers at the middle of the layer's gap the plan runs through.
  void centre_in_layer_gap(const ExploreInput& input, core::DriveCommand& command);
  bool plan_passes_between(const Eigen::Vector2d& robot, const Eigen::Vector2d& left, const Eigen::Vector2d& right) const;
  Blocked disc_blocked(const GridView& grid, const Eigen::Vector2d& centre, const Eigen::Vector2d& robot,
                       const ExploreInput& input) const;
  bool grid_blocks_disc(const GridView& grid, const Eigen::Vector2d& centre, const Eigen::Vector2d& robot,
                        double time_s) const;
  bool scan_blocks_disc(const SeenObstacles& seen, const Eigen::Vector2d& centre, const Eigen::Vector2d& robot) const;
  bool scan_guard_active(const ExploreInput& input) const;
  bool scan_blocks_stretch(const ExploreInput& input) const;
  Eigen::Vector2i cell_of(const core::Pose2& pose) const;
  // Where the stall detector measures the travel from (explore.stall_from_odometry).
  Eigen::Vector2d stall_position(const ExploreInput& input) const;
  void note(ExploreEventKind kind, const ExploreInput& input);  // with the goal and its value
  void note(ExploreEventKind kind, const ExploreInput& input, const Eigen::Vector2d& where, double value);
  void note_sighting(const ExploreInput& input);

  ExploreParams params_;
  NavigationMap map_;
  GoalValue goal_value_;
  GoalMemory memory_;
  StallDetector stall_;
  ContactMemory contacts_;
  ShutGaps gaps_;
  RecentObstacles recent_;
  TraceMemory traces_;
  TrailMemory trail_;
  ExploreJournal journal_;
  GridView planning_grid_;  // the input grid with the contact, shut gap and recent obstacle cells occupied (last rebuild): the safety check's
  bool planning_on_copy_ = false;  // planning_grid_ is a stamped copy (contacts, shut gaps, recent obstacles)
  bool crossing_traces_ = false;   // the navigation map holds a person's old traces free
  bool following_trail_ = false;   // ... and the robot's own path open
  std::size_t trail_cells_opened_ = 0;  // by the last rebuild
  bool stalled_ = false;           // this tick
  bool holding_for_scan_ = false;  // standing still for what the scan guard saw
  double scan_hold_until_s_ = 0.0;  // the last blocking scan's time + scan_guard_max_age_s
  PathPlanner planner_;
  PathFollower follower_;
  DoorAxis door_axis_;
  DoorSighting sighting_;
  DoorStandoff standoff_;
  ExploreInput navigation_input_;
  // The latest scan's points were placed with the estimate's pose: moved by the sighting's
  // correction now (none without one), they lie where the navigation pose puts them.
  core::Pose2 seen_correction_;
  Plan plan_;
  Plan fresh_plan_;  // plan_switch_saving_m: the fresh plan weighed against the kept one
  Goal goal_;
  ExploreCounters counters_;
  ExploreState state_ = ExploreState::look_around;
  FinishReason finish_reason_ = FinishReason::none;
  bool started_ = false;
  bool rebuild_needed_ = true;
  core::Pose2 start_pose_;
  double start_time_s_ = 0.0;
  // Look around.
  int look_step_ = 0;
  double look_turned_rad_ = 0.0;
  double look_last_heading_ = 0.0;
  double look_began_s_ = 0.0;  // begin_look's time: trace_confirm_before_look
  double pan_target_rad_ = 0.0;
  // Backing off after a stall (or to see a trace).
  bool backing_off_ = false;
  double back_off_m_ = 0.0;
  Eigen::Vector2d back_off_from_ = Eigen::Vector2d::Zero();
  double back_off_start_s_ = 0.0;
  bool back_off_turning_ = false;      // turning in place first (stall_back_off_turn_deg)
  double back_off_heading_rad_ = 0.0;  // ... to this heading
  double back_off_turn_until_s_ = 0.0;  // ... for at most twice the time the turn needs
  bool fresh_look_ = false;         // a look ended here and no plan has been found since
  bool return_after_look_ = false;  // after the look: back on the way to the start
  bool resume_after_look_ = false;  // after the look: back on the way to the same goal
  bool keep_progress_after_look_ = false;  // the look was a safety stop's: keep the stuck timer
  // Progress towards the goal: the plan's remaining length, and how long the goal may take.
  double best_goal_distance_m_ = 0.0;
  double last_progress_time_s_ = 0.0;
  double goal_started_s_ = 0.0;
  double longest_plan_m_ = 0.0;
  double first_plan_m_ = 0.0;  // its first plan's length, for goal_time_first_plan
  // Net progress: the shortest remaining length of any of the goal's plans, and when it was.
  double nearest_remaining_m_ = 0.0;
  double nearest_remaining_time_s_ = 0.0;
  int blocked_plans_ = 0;  // this goal's plans found blocked (max_blocked_plans)
  int plan_reversals_ = 0;  // ... and replaced by one leading back (max_plan_reversals)
  // Plans kept for passers-by (wait_for_walkers): the time spent so on this goal (or the way back).
  bool waiting_for_walkers_ = false;
  double walker_wait_since_s_ = 0.0;
  double walker_waited_s_ = 0.0;
  double walker_hold_until_s_ = 0.0;  // standing still for a kept plan's passer-by until then (walker_hold_s)
};

}  // namespace stereoscout::explore
