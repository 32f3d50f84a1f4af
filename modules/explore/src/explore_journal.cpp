#include "stereoscout/explore/explore_journal.hpp"

namespace stereoscout::explore {

const char* to_string(ExploreEventKind kind) {
  switch (kind) {
    case ExploreEventKind::goal_chosen: return "goal_chosen";
    case ExploreEventKind::goal_reached: return "goal_reached";
    case ExploreEventKind::goal_abandoned: return "goal_abandoned";
    case ExploreEventKind::plan_blocked: return "plan_blocked";
    case ExploreEventKind::no_plan: return "no_plan";
    case ExploreEventKind::stuck: return "stuck";
    case ExploreEventKind::goal_timeout: return "goal_timeout";
    case ExploreEventKind::no_net_progress: return "no_net_progress";
    case ExploreEventKind::blocked_too_often: return "blocked_too_often";
    case ExploreEventKind::goal_failed: return "goal_failed";
    case ExploreEventKind::goal_blacklisted: return "goal_blacklisted";
    case ExploreEventKind::safety_stop: return "safety_stop";
    case ExploreEventKind::backing_to_see: return "backing_to_see";
    case ExploreEventKind::scan_stop: return "scan_stop";
    case ExploreEventKind::stall: return "stall";
    case ExploreEventKind::look: return "look";
    case ExploreEventKind::contacts_cleared: return "contacts_cleared";
    case ExploreEventKind::blacklist_released: return "blacklist_released";
    case ExploreEventKind::crossing_traces: return "crossing_traces";
    case ExploreEventKind::following_trail: return "following_trail";
    case ExploreEventKind::plan_kept: return "plan_kept";
    case ExploreEventKind::walker_hold: return "walker_hold";
    case ExploreEventKind::plan_switched: return "plan_switched";
    case ExploreEventKind::explored: return "explored";
    case ExploreEventKind::time_limit: return "time_limit";
    case ExploreEventKind::return_failed: return "return_failed";
    case ExploreEventKind::returned: return "returned";
    case ExploreEventKind::door_sighted: return "door_sighted";
    case ExploreEventKind::door_standoff: return "door_standoff";
    case ExploreEventKind::gap_shut: return "gap_shut";
    case ExploreEventKind::shut_gaps_lifted: return "shut_gaps_lifted";
    case ExploreEventKind::plan_reversed: return "plan_reversed";
    case ExploreEventKind::reversed_too_often: return "reversed_too_often";
  }
  return "?";
}

}  // namespace stereoscout::explore
