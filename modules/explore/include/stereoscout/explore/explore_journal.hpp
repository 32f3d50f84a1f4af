#pragma once
// What the explorer decided and why, event by event: the flight recorder of exploration.
// Counters say how often a goal failed; the journal says which goal, where the robot stood,
// and what came before (a stall, a look, a replan), which is what a run that covered too
// little must be read from. The run directory writes it as explore_events.csv
// (docs/report.md).
//
// A fixed ring of explore.event_memory events, allocated at start-up: when it is full the
// oldest event is dropped and counted (dropped()), as in a flight recorder, whose last
// minutes matter most. Events come at most a few per second (goals, replans, looks, stops),
// never one per tick.

#include <cstddef>
#include <cstdint>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/ring_buffer.hpp"

namespace stereoscout::explore {

enum class ExploreEventKind : std::uint8_t {
  goal_chosen,       // a new goal, planned to
  goal_reached,
  goal_abandoned,    // its value fell below min_goal_value on the way
  plan_blocked,      // an update made the rest of the plan impassable: replanning
  plan_kept,         // ... only by passers-by: kept (wait_for_walkers; once a span)
  walker_hold,       // ... by a passer-by near the robot: it stands still for walker_hold_s
  plan_switched,     // a fresh plan costs plan_switch_saving_m less than the rest of the kept one: taken
  no_plan,           // A* found no path to the goal (or the start)
  stuck,             // no progress along the plan for stuck_timeout_s
  goal_timeout,      // pursued longer than its plans' driving time allows (goal_time_factor)
  no_net_progress,   // no nearer to it than ever before, along any plan, for net_progress_timeout_s
  blocked_too_often, // its plans were found blocked max_blocked_plans times
  goal_failed,       // the goal is given up (after no_plan, stuck, goal_timeout, no_net_progress, blocked_too_often or reversed_too_often)
  goal_blacklisted,  // ... for blacklist_hold_s (0: for good): it failed goal_failures_before_blacklist times
  safety_stop,       // the next stretch would touch an occupied cell
  backing_to_see,    // ... a person's old trace, where the camera sees no floor: backing off before the look
  scan_stop,         // ... the grid clear, but the latest scan saw an obstacle there (scan_guard_min_points)
  stall,             // forward motion commanded, none made: a contact
  look,              // a 360-degree look begins
  contacts_cleared,  // before concluding "explored" or "no way back"
  blacklist_released,  // before concluding "explored": held blacklisted goals may be chosen again
  crossing_traces,   // before concluding "no plan" or "explored": a person's old traces are crossed
  following_trail,   // before concluding "explored" or "no way back": plans may follow the robot's own path
  explored,          // no goal worth min_goal_value is left
  time_limit,        // explore.time_limit_s reached
  return_failed,     // no way back to the start, or no progress on it
  returned,          // back at the start
  door_sighted,      // a scan saw the door on the plan: the pose navigated by is corrected across it
  door_standoff,     // at the door's standoff point (explore.door_standoff_m): turning to face the door
  gap_shut,          // a goal failed at a gap shut from near that the robot never drove through (shut_gap_hold_s)
  shut_gaps_lifted,  // before concluding "explored" or "no way back"
  plan_reversed,     // a blocked plan's replacement leads back, more than plan_reversal_deg off the heading
  reversed_too_often,  // max_plan_reversals of its plans did (the goal fails)
};
const char* to_string(ExploreEventKind kind);

struct ExploreEvent {
  double time_s = 0.0;
  ExploreEventKind kind = ExploreEventKind::goal_chosen;
  core::Pose2 pose;  // the robot's, as the explorer had it (the ML particle's)
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();  // the goal at the time (the start when returning)
  double goal_value = 0.0;                         // H(goal) when chosen; 0 for the start
};

class ExploreJournal {
 public:
  explicit ExploreJournal(std::size_t capacity) : events_(capacity) {}

  void record(const ExploreEvent& event) { events_.push_overwrite(event); }

  std::size_t size() const { return events_.size(); }
  const ExploreEvent& operator[](std::size_t i) const { return events_[i]; }  // 0 = oldest kept
  std::uint64_t recorded() const { return events_.pushed(); }
  std::uint64_t dropped() const { return events_.overwritten(); }

 private:
  core::RingBuffer<ExploreEvent> events_;
};

}  // namespace stereoscout::explore
