#include "stereoscout/explore/explorer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stereoscout::explore {
namespace {

// The pan unit turns the shortest way to its target, so four quarter turns make one full
// counter-clockwise look that ends facing forward.
constexpr double kLookTargets_deg[] = {90.0, 180.0, -90.0, 0.0};
constexpr int kLookSteps = 4;
constexpr double kPanReached_rad = 0.02;
// Progress towards a goal counts when the distance shrinks by at least this much.
constexpr double kProgressStep_m = 0.1;
// The point ahead of the robot checked before moving forward.
constexpr double kAheadCheck_m = 0.15;
// Scan points this far inside the robot's rim where it stands are under it (a person who
// walked into the robot), not something it drives into: the grid's rule uses a cell.
constexpr double kScanGuardDeep_m = 0.1;
// The layer's gap (explore.layer_gap_reach_m): its points from the robot's radius behind its
// centre to this far ahead (the approach to a door; farther, the follower's own lookahead
// governs), its two sides within kLayerGapSquare_m of each other along the way (a door seen
// 20 degrees or more off square is still being turned into), the plan run through it within
// kLayerGapPlan_m, where the line between its sides, stretched kLayerGapSlack_m either end
// (the plan's grid and the layer differ by the pose's error), meets the plan.
constexpr double kLayerGapAhead_m = 0.8;
constexpr double kLayerGapSquare_m = 0.3;
constexpr double kLayerGapPlan_m = 1.5;
constexpr double kLayerGapSlack_m = 0.2;
// Facing the plan's next waypoint: within this angle of it (at 8 deg/s a 20 Hz drive tick turns 0.4 deg).
constexpr double kFacingPlan_rad = 0.05;
// Back-off headings tried, from the stalled heading out to stall_back_off_turn_deg either side.
constexpr double kBackOffTurnStep_deg = 15.0;
// A way back is checked at points this many cells apart.
constexpr double kBackOffCheckStep_cells = 0.5;
// A heading turned to for a back-off must leave at least this part of it clear: any move out
// of the wedge brings updates, and a whole clear back-off is rare in a door (office seed 1 with
// the random walk: every turn of up to 60 deg met a cell within 0.30 m).
constexpr double kBackOffLeastFraction = 0.5;
// Goals tried per tick when planning to the best ones fails.
constexpr int kGoalAttemptsPerTick = 4;

// A cell or point the disc already overlaps where the robot stands does not stop it, unless
// the move goes deeper into it (a grazed obstacle: pushing on would be a collision); those
// deep under the robot are traces of a person who walked into it (NavigationMap ignores them).
bool move_touches(const Eigen::Vector2d& obstacle, const Eigen::Vector2d& centre, const Eigen::Vector2d& robot,
                  double radius, double deep) {
  const double ahead = (obstacle - centre).norm();
  if (ahead >= radius) return false;
  const double now = (obstacle - robot).norm();
  return now >= radius || (now >= deep && ahead < now);
}

Eigen::Vector2d position_of(const core::Pose2& pose) { return {pose.x, pose.y}; }

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// The segments a0-a1 and b0-b1 meet (touching counts).
bool segments_meet(const Eigen::Vector2d& a0, const Eigen::Vector2d& a1, const Eigen::Vector2d& b0,
                   const Eigen::Vector2d& b1) {
  const Eigen::Vector2d a = a1 - a0;
  const Eigen::Vector2d b = b1 - b0;
  const double d1 = cross(a, b0 - a0);
  const double d2 = cross(a, b1 - a0);
  const double d3 = cross(b, a0 - b0);
  const double d4 = cross(b, a1 - b0);
  return d1 * d2 <= 0.0 && d3 * d4 <= 0.0;
}

Eigen::Vector2d unit_towards(double heading_rad) { return {std::cos(heading_rad), std::sin(heading_rad)}; }

// The part of the camera's view at this update in which a cell that stays occupied is seen
// standing (trace_memory.hpp).
CameraWedge camera_wedge(const ExploreParams& params, const ExploreInput& input) {
  CameraWedge view;
  view.position = position_of(input.pose) + params.camera_forward_m * unit_towards(input.pose.theta);
  view.heading_rad = input.pose.theta + input.pan_rad;
  view.half_fov_rad = params.camera_half_fov_rad;
  view.near_m = params.camera_near_m;
  view.far_m = params.explore.trace_confirm_radius_m;
  return view;
}

}  // namespace

const char* to_string(ExploreState state) {
  switch (state) {
    case ExploreState::look_around: return "look_around";
    case ExploreState::choose_goal: return "choose_goal";
    case ExploreState::drive: return "drive";
    case ExploreState::returning: return "returning";
    case ExploreState::finished: return "finished";
  }
  return "?";
}

Explorer::Explorer(const ExploreParams& params)
    : params_(params),
      map_(params),
      goal_value_(params),
      memory_(static_cast<std::size_t>(params.explore.goal_memory), params.explore.visited_goal_radius_m,
              params.explore.blacklist_radius_m, params.explore.goal_failures_before_blacklist,
              params.explore.failed_goal_cooldown_s, params.explore.blacklist_hold_s,
              params.explore.goal_failure_radius_m),
      stall_(params.explore),
      contacts_(params.explore, params.max_width, params.max_height),
      gaps_(params, params.max_width, params.max_height),
      recent_(params.explore, params.max_width, params.max_height),
      traces_(params.explore, params.max_width, params.max_height),
      trail_(params.explore),
      journal_(static_cast<std::size_t>(params.explore.event_memory)),
      planner_(params),
      follower_(params),
      door_axis_(params),
      sighting_(params),
      standoff_(params),
      plan_(static_cast<std::size_t>(params.explore.max_plan_waypoints)),
      // Only the plan switch plans into the second plan: without it, it holds nothing.
      fresh_plan_(params.explore.plan_switch_saving_m > 0.0 ? static_cast<std::size_t>(params.explore.max_plan_waypoints)
                                                             : 0) {}

Eigen::Vector2d Explorer::stall_position(const ExploreInput& input) const {
  return params_.explore.stall_from_odometry ? position_of(input.odometry) : position_of(input.pose);
}

Eigen::Vector2i Explorer::cell_of(const core::Pose2& pose) const { return map_.grid().cell_of(position_of(pose)); }

void Explorer::note(ExploreEventKind kind, const ExploreInput& input) {
  note(kind, input, goal_.position, goal_.value);
}

void Explorer::note(ExploreEventKind kind, const ExploreInput& input, const Eigen::Vector2d& where, double value) {
  ExploreEvent event;
  event.time_s = input.time_s;
  event.kind = kind;
  event.pose = input.pose;
  event.goal = where;
  event.goal_value = value;
  journal_.record(event);
}

// The door's middle in the grid where other events have the goal, and the correction across
// the door where they have its value.
void Explorer::note_sighting(const ExploreInput& input) {
  const Eigen::Vector2d across(-sighting_.door().along.y(), sighting_.door().along.x());
  note(ExploreEventKind::door_sighted, input, sighting_.door().middle, sighting_.last_offset().dot(across));
}

const ExploreInput& Explorer::navigation_input(const ExploreInput& input) {
  if (!sighting_.enabled()) return input;
  navigation_input_ = input;
  navigation_input_.pose = sighting_.navigation_pose(input.pose, input.odometry);
  if (sighting_.wants(input.seen)) {
    DoorPassage door;
    const bool driving = state_ == ExploreState::drive || state_ == ExploreState::returning;
    if (driving && !plan_.empty()) {
      find_door(plan_, follower_.progress(), map_, position_of(navigation_input_.pose),
                params_.explore.door_sighting_range_m + params_.robot_radius_m, false,
                params_.safe_distance_m(map_.grid().resolution_m), door);
    }
    const std::uint64_t sightings = sighting_.counters().sightings;
    sighting_.observe(input.seen, door, planning_grid_);
    navigation_input_.pose = sighting_.navigation_pose(input.pose, input.odometry);
    if (sighting_.counters().sightings > sightings) note_sighting(navigation_input_);
  }
  seen_correction_ = sighting_.holding() ? navigation_input_.pose.compose(input.pose.inverse()) : core::Pose2{};
  return navigation_input_;
}

ExploreOutput Explorer::step(const ExploreInput& raw_input) {
  const ExploreInput& input = navigation_input(raw_input);
  if (!started_) start(input);
  trail_.record(position_of(input.pose));
  gaps_.drove(map_.grid(), position_of(input.pose));
  recent_.observe(input.seen);
  stalled_ = stall_.stalled(input.time_s, stall_position(input));
  ExploreOutput output;
  if (input.emergency_stop) {
    // Halt within this very tick: zero velocity, pan held where it is; the state is kept so
    // that exploration resumes when the stop is released.
    ++counters_.emergency_stop_ticks;
    output.pan_target_rad = input.pan_rad;
    output.state = state_;
    rebuild_needed_ = rebuild_needed_ || input.grid_updated;
    stall_.commanded(input.time_s, stall_position(input), 0.0);
    return output;
  }
  if (backing_off_) {
    // Away from the contact first; the map is rebuilt and the plan checked after the look.
    rebuild_needed_ = rebuild_needed_ || input.grid_updated;
    if (!back_off_step(input, output)) stop_and_look(input, output, 0.0);
    output.pan_target_rad = pan_target_rad_;
    output.state = state_;
    stall_.commanded(input.time_s, stall_position(input), output.drive.linear_mps);
    return output;
  }
  if (input.grid_updated || rebuild_needed_) rebuild(input);
  const bool exploring = (state_ == ExploreState::look_around && !return_after_look_) ||
                         state_ == ExploreState::choose_goal || state_ == ExploreState::drive;
  if (exploring && input.time_s - start_time_s_ >= params_.explore.time_limit_s) {
    finish_exploring(input, FinishReason::time_limit);
  }
  // In this order so that a finished look chooses a goal and starts driving in the same tick.
  if (state_ == ExploreState::look_around) look_step(input, output);
  if (state_ == ExploreState::choose_goal) choose_goal(input);
  if (state_ == ExploreState::drive || state_ == ExploreState::returning) drive_step(input, output);
  output.pan_target_rad = pan_target_rad_;
  output.state = state_;
  stall_.commanded(input.time_s, stall_position(input), output.drive.linear_mps);
  return output;
}

void Explorer::start(const ExploreInput& input) {
  started_ = true;
  start_pose_ = input.pose;
  start_time_s_ = input.time_s;
  rebuild_needed_ = true;
  if (params_.explore.pan_at_goal) {
    begin_look(input);
  } else {
    state_ = ExploreState::choose_goal;
  }
}

void Explorer::rebuild(const ExploreInput& input) {
  rebuild_needed_ = false;
  const CameraWedge view = camera_wedge(params_, input);
  traces_.observe(input.grid, input.time_s, &view);
  counters_.traces_seen_standing = traces_.seen_standing();
  rebuild_map(input);
  if (state_ == ExploreState::drive || state_ == ExploreState::returning) check_plan(input);
}

void Explorer::rebuild_map(const ExploreInput& input) {
  // Unknown cells may be crossed near the robot and near the start, all the run: the robot
  // started in a disc the camera could not see (its floor was too near), and the strip of it
  // that no later view covered splits the corridor it started in (the office: the way out of
  // the first office led through it).
  const Eigen::Vector2d extra = position_of(start_pose_);
  const GridView remembered = gaps_.stamp(contacts_.stamp(input.grid, input.time_s), input.time_s);
  planning_grid_ = recent_.stamp(remembered, input.pose, input.odometry, input.time_s);
  planning_on_copy_ = planning_grid_.cells != input.grid.cells;
  // While crossing traces, plans cross a person's old traces; the safety check (on
  // planning_grid_) never does.
  GridView navigation_grid = crossing_traces_ ? traces_.forget_traces(planning_grid_, input.time_s) : planning_grid_;
  if (params_.explore.remembered_obstacle_cost > 0.0) navigation_grid.seen_standing = traces_.standing_cells();
  map_.rebuild(navigation_grid, position_of(input.pose), extra);
  trail_cells_opened_ = following_trail_ ? map_.open_trail(trail_) : 0;
  ++counters_.map_rebuilds;
}

// Contact cells lie where the pose estimate put the robot's rim, and a door whose jamb the robot
// touched (a contact ahead, another backing out) can be closed by them for contact_hold_s.
// So neither "nothing left" nor "no way back" is concluded on them: they are forgotten and the
// map rebuilt first. True when there were any. A contact that was real is made again by the
// next stall, and that one is kept through later clears (contact_repeat_radius_m): the
// explorer concludes on it rather than drive into the same surface after every clear.
bool Explorer::clear_contacts(const ExploreInput& input) {
  if (contacts_.clear() == 0) return false;
  ++counters_.contact_clears;
  note(ExploreEventKind::contacts_cleared, input);
  rebuild_map(input);
  return true;
}

// A goal failed at a gap that a view shut and the robot never drove through
// (shut_gaps.hpp): the gap stays shut for planning, so no goal behind it is chosen next.
void Explorer::shut_gap(const ExploreInput& input) {
  if (!gaps_.shut(input.time_s)) return;
  note(ExploreEventKind::gap_shut, input, gaps_.last_shut_at(), static_cast<double>(gaps_.last_shut_cells()));
  rebuild_map(input);
}

// Shut gaps hold for shut_gap_hold_s, but "nothing left" and "no way back" are not concluded
// on them: they are lifted and the map rebuilt first. True when there were any.
bool Explorer::lift_shut_gaps(const ExploreInput& input) {
  if (gaps_.lift() == 0) return false;
  ++counters_.shut_gap_lifts;
  note(ExploreEventKind::shut_gaps_lifted, input);
  rebuild_map(input);
  return true;
}

// A goal blacklisted for what was in the robot's way at the time (its own door narrowed for a
// moment) excludes candidates within blacklist_radius_m for blacklist_hold_s, and with them the
// places the frontier behind it is seen from: "nothing left" would then be concluded on goals
// only put aside. So their holds are lifted first, each goal's at most blacklist_releases times,
// and a room the robot cannot enter still lets the run end. True when any was held.
bool Explorer::release_blacklist(const ExploreInput& input) {
  if (memory_.release_held(input.time_s, params_.explore.blacklist_releases) == 0) return false;
  ++counters_.blacklist_releases;
  note(ExploreEventKind::blacklist_released, input);
  return true;
}

// A person who walked past a door while the robot looked out of the room leaves cells beyond
// it that no view from inside clears, and they can shut the robot in. So neither "no plan" nor
// "nothing left" is concluded on a person's old traces (trace_memory.hpp): the map is rebuilt
// with them free, and the plans on it cross them until the goal is reached or fails. True when
// there were any. The safety check still stops the robot before such a cell; the look that
// follows clears it, or confirms it as an obstacle.
bool Explorer::start_crossing_traces(const ExploreInput& input) {
  if (crossing_traces_ || params_.explore.trace_forget_after_s <= 0.0) return false;
  return start_last_resort(crossing_traces_, [this] { return traces_.forgotten_last() > 0; },
                           ExploreEventKind::crossing_traces, counters_.trace_crossings, input);
}

// The passage the robot came in by can close behind it: a cell smeared at its edge narrows it
// below the lethal width, and the robot, boxed in, would conclude "explored" and then "no way
// back". It drove through, so the floor is there: before concluding, plans may follow its
// trail (trail_memory.hpp) until the goal (or the way back) is reached or fails. True when the
// trail opened any cell. Only then: a run that never concludes so plans as without it.
bool Explorer::start_following_trail(const ExploreInput& input) {
  if (following_trail_ || !trail_.enabled()) return false;
  return start_last_resort(following_trail_, [this] { return trail_cells_opened_ > 0; },
                           ExploreEventKind::following_trail, counters_.trail_follows, input);
}

// Switches one last resort on (a flag rebuild_map() reads) and keeps it only when the map it
// rebuilt differs: counted and journaled then.
template <typename Changed>
bool Explorer::start_last_resort(bool& active, Changed&& changed, ExploreEventKind kind, std::uint64_t& count,
                                 const ExploreInput& input) {
  active = true;
  rebuild_map(input);
  if (!changed()) {
    active = false;  // the same map as before
    return false;
  }
  ++count;
  note(kind, input);
  return true;
}

// Crossing traces and following the trail end with the goal they were for.
void Explorer::stop_last_resorts(const ExploreInput& input) {
  if (!crossing_traces_ && !following_trail_) return;
  crossing_traces_ = false;
  following_trail_ = false;
  rebuild_map(input);
}

// After every observation update: is the rest of the plan still passable? Is the goal still
// worth going to (it may have been seen on the way)?
void Explorer::check_plan(const ExploreInput& input) {
  if (state_ == ExploreState::drive &&
      goal_value_.value(map_, goal_.cell.x(), goal_.cell.y()) <= params_.explore.min_goal_value) {
    ++counters_.goals_abandoned;
    note(ExploreEventKind::goal_abandoned, input);
    plan_.clear();
    stop_last_resorts(input);
    state_ = ExploreState::choose_goal;
    return;
  }
  for (std::size_t k = follower_.progress() + 1; k < plan_.cells.size(); ++k) {
    if (!map_.passable(plan_.cells[k].x(), plan_.cells[k].y())) {
      const bool by_passers_by = blocked_by_passers_by(input, plan_.cells[k]);
      if (by_passers_by && may_wait_for_walkers(input)) {
        ++counters_.plans_kept_for_walkers;
        hold_for_walker(input, plan_.cells[k]);
        return;
      }
      stop_waiting_for_walkers(input.time_s);
      ++counters_.replans;
      note(ExploreEventKind::plan_blocked, input);
      ++blocked_plans_;
      if (blocked_too_often()) {
        ++counters_.blocked_plan_limits;
        note(ExploreEventKind::blocked_too_often, input);
        goal_failed(input);
        return;
      }
      // A person's traces shut nothing for good: they pass.
      if (!by_passers_by) gaps_.blocked(map_, plan_, k, position_of(input.pose));
      if (replan(input)) {
        gaps_.forget_blocked();
        if (reversed_too_often(input)) {
          ++counters_.reversal_limits;
          note(ExploreEventKind::reversed_too_often, input);
          goal_failed(input);
        }
        return;
      }
      shut_gap(input);
      goal_failed(input);
      return;
    }
  }
  stop_waiting_for_walkers(input.time_s);
  if (switch_to_cheaper_plan(input)) return;
  if (params_.explore.refit_kept_plans) planner_.refit(map_, plan_, follower_.progress() + 1);
}

// The kept plan was the cheapest on the map it was made on. A cell that turned impassable
// replans it (above); one that turned costly, such as a door's far jamb mapped since and
// putting the crossing within its safety margin, does not. A fresh plan to the same cell is
// taken only when it is clearly cheaper, so that two near-equal ways do not alternate.
bool Explorer::switch_to_cheaper_plan(const ExploreInput& input) {
  const double saving = params_.explore.plan_switch_saving_m;
  if (saving <= 0.0 || plan_.cells.size() < 2 || crossing_traces_ || following_trail_ || !narrow_ahead()) return false;
  const double kept = PathPlanner::remaining_cost(map_, plan_, follower_.progress());
  if (planner_.plan(map_, cell_of(input.pose), plan_.cells.back(), fresh_plan_) != PlanResult::found ||
      fresh_plan_.cost > kept - saving) {
    return false;
  }
  plan_.swap(fresh_plan_);
  follower_.reset();
  ++counters_.plans_switched;
  note(ExploreEventKind::plan_switched, input);
  note_plan_length(input);
  return true;
}

// Whether a cell of the kept plan ahead of the robot, up to the first waypoint at or past
// plan_switch_within_m along it, is narrow on the rebuilt map.
bool Explorer::narrow_ahead() const {
  const double within = params_.explore.plan_switch_within_m;
  if (within <= 0.0) return true;
  const std::size_t first = follower_.progress();
  double along = 0.0;
  for (std::size_t k = first + 1; k < plan_.cells.size() && along <= within; ++k) {
    along += (plan_.waypoints[k] - plan_.waypoints[k - 1]).norm();
    if (planner_.narrow(map_, plan_.cells[k].x(), plan_.cells[k].y())) return true;
  }
  return false;
}

// A longer plan is a detour the map now demands (a wall where it held free cells): progress
// is measured along it, not against the shorter plan's best.
void Explorer::note_plan_length(const ExploreInput& input) {
  const double length = remaining_path_m(position_of(input.pose));
  longest_plan_m_ = std::max(longest_plan_m_, length);
  if (first_plan_m_ <= 0.0) first_plan_m_ = length;
  if (std::isfinite(best_goal_distance_m_)) best_goal_distance_m_ = std::max(best_goal_distance_m_, length);
}

// A plan that the next view blocks, again and again, runs through a gap each view opens and
// the next closes: a blank wall's cells, erased by grazing rays, restored piece by piece. The
// way back is never given up so.
bool Explorer::blocked_too_often() const {
  const int limit = params_.explore.max_blocked_plans;
  return limit > 0 && state_ != ExploreState::returning && blocked_plans_ >= limit;
}

// Two ways to a goal that views block in turn (a door the robot cannot pass, gaps in a blank
// wall) turn the robot about at each block: at 8 degrees a second each half turn costs 20 s,
// and the next block undoes it. Counts the replacements that lead back; the way back is
// never given up so.
bool Explorer::reversed_too_often(const ExploreInput& input) {
  const int limit = params_.explore.max_plan_reversals;
  if (limit <= 0 || !leads_back(input.pose)) return false;
  ++plan_reversals_;
  ++counters_.plan_reversals;
  note(ExploreEventKind::plan_reversed, input);
  return state_ != ExploreState::returning && plan_reversals_ >= limit;
}

// Whether the plan leaves the robot more than plan_reversal_deg off its heading, judged at
// its first waypoint a lookahead away (the nearest lie within the robot's own cell). A plan
// that ends nearer gives no direction.
bool Explorer::leads_back(const core::Pose2& pose) const {
  if (plan_.empty()) return false;
  const Eigen::Vector2d position = position_of(pose);
  const double lookahead_m = params_.explore.lookahead_m;
  const Eigen::Vector2d ahead = follower_.point_ahead(plan_, position, lookahead_m) - position;
  if (ahead.norm() < lookahead_m) return false;
  const double off = core::wrap_angle(std::atan2(ahead.y(), ahead.x()) - pose.theta);
  return std::abs(off) > core::degrees_to_radians(params_.explore.plan_reversal_deg);
}

// A passer-by has walked on within seconds; a plan that stays blocked longer is blocked by
// something that looks the same to the trace memory, such as a blank wall's restored cells.
// So one goal's kept plans may take walker_wait_per_goal_s in all.
bool Explorer::may_wait_for_walkers(const ExploreInput& input) {
  const double since_s = waiting_for_walkers_ ? walker_wait_since_s_ : input.time_s;
  if (walker_waited_s_ + (input.time_s - since_s) > params_.explore.walker_wait_per_goal_s) {
    ++counters_.walker_waits_ended;
    return false;
  }
  if (!waiting_for_walkers_) {
    waiting_for_walkers_ = true;
    walker_wait_since_s_ = input.time_s;
    note(ExploreEventKind::plan_kept, input);
  }
  return true;
}

// A passer-by whose cells block the kept plan near the robot is still beside its way: driving
// on, or turning to face the plan, met the walker (the lab, seed 2, 5 cm grid: the robot turned
// in place, then drove into the walker 0.6 m to its right, nearer than the matcher measures).
// The first blocked cell along the plan stands for the passer-by.
void Explorer::hold_for_walker(const ExploreInput& input, const Eigen::Vector2i& blocked_cell) {
  if (params_.explore.walker_hold_s <= 0.0 || input.time_s < walker_hold_until_s_) return;
  const double within = params_.explore.walker_hold_within_m;
  if ((map_.grid().center(blocked_cell.x(), blocked_cell.y()) - position_of(input.pose)).squaredNorm() > within * within) {
    return;
  }
  walker_hold_until_s_ = input.time_s + params_.explore.walker_hold_s;
  ++counters_.walker_holds;
  note(ExploreEventKind::walker_hold, input);
}

void Explorer::stop_waiting_for_walkers(double time_s) {
  if (!waiting_for_walkers_) return;
  waiting_for_walkers_ = false;
  walker_waited_s_ += time_s - walker_wait_since_s_;
}

// A person crossing the plan ahead leaves cells that block it for a few updates; replanning
// sent the robot on a detour, and the next crossing on another (wait_for_walkers). Kept when
// the cell is known and only such recent cells, not seen standing, block it.
bool Explorer::blocked_by_passers_by(const ExploreInput& input, const Eigen::Vector2i& cell) const {
  if (!params_.explore.wait_for_walkers || planning_grid_.at(cell.x(), cell.y()) == CellState::unknown) return false;
  return traces_.only_passers_by_near(planning_grid_, cell.x(), cell.y(),
                                      params_.lethal_distance_m(planning_grid_.resolution_m), input.time_s);
}

bool Explorer::plan_to_goal(const ExploreInput& input) {
  Eigen::Vector2i target = goal_.cell;
  if (!map_.passable(target.x(), target.y()) &&
      map_.nearest_passable(goal_.cell, params_.explore.goal_shift_radius_m, target)) {
    ++counters_.goal_shifts;
  }
  return planner_.plan(map_, cell_of(input.pose), target, plan_) == PlanResult::found;
}

bool Explorer::replan(const ExploreInput& input) {
  follower_.reset();
  const bool returning = state_ == ExploreState::returning;
  if (plan_to_goal(input) || (returning && clear_contacts(input) && plan_to_goal(input)) ||
      (returning && lift_shut_gaps(input) && plan_to_goal(input)) ||
      (start_crossing_traces(input) && plan_to_goal(input)) ||
      (returning && start_following_trail(input) && plan_to_goal(input))) {
    fresh_look_ = false;  // the robot drives on: the next failure deserves a look of its own
    note_plan_length(input);
    return true;
  }
  ++counters_.plan_failures;
  note(ExploreEventKind::no_plan, input);
  return false;
}

// A new goal (or the way back): progress starts from nothing, and so does its time.
void Explorer::begin_pursuit(const ExploreInput& input) {
  best_goal_distance_m_ = std::numeric_limits<double>::infinity();
  last_progress_time_s_ = input.time_s;
  goal_started_s_ = input.time_s;
  longest_plan_m_ = 0.0;
  first_plan_m_ = 0.0;
  nearest_remaining_m_ = std::numeric_limits<double>::infinity();
  nearest_remaining_time_s_ = input.time_s;
  blocked_plans_ = 0;
  plan_reversals_ = 0;
}

void Explorer::begin_walker_waits() {
  waiting_for_walkers_ = false;
  walker_waited_s_ = 0.0;
}

// What is left of the plan: to the waypoint the follower is at, then along the rest. A plan
// around a wall is longer than the straight line to the goal and, for a while, leads away
// from it; along the plan the robot makes progress all the same.
double Explorer::remaining_path_m(const Eigen::Vector2d& position) const {
  if (plan_.empty()) return (position - goal_.position).norm();
  std::size_t k = std::min(follower_.progress(), plan_.waypoints.size() - 1);
  double length = (plan_.waypoints[k] - position).norm();
  for (; k + 1 < plan_.waypoints.size(); ++k) length += (plan_.waypoints[k + 1] - plan_.waypoints[k]).norm();
  return length;
}

// Progress along each new plan resets the stuck timer, so a robot that alternates between two
// routes (a gap in a wall that the next view closes, a door) would never fail: the goal gets
// stuck_timeout_s plus goal_time_factor times its longest (or first) plan's driving time.
bool Explorer::out_of_time(double time_s) const {
  if (params_.explore.goal_time_factor <= 0.0) return false;
  const double plan_m = params_.explore.goal_time_first_plan ? first_plan_m_ : longest_plan_m_;
  const double driving_s = plan_m / params_.max_speed_mps;
  return time_s - goal_started_s_ > params_.explore.stuck_timeout_s + params_.explore.goal_time_factor * driving_s;
}

// Progress along the current plan restarts with each longer plan (above); a robot that goes
// back and forth between a route through a gap that one view opens and the next closes (a
// blank wall) and the long way round progresses on each and gets no nearer.
void Explorer::track_net_progress(double remaining_m, double time_s) {
  if (remaining_m >= nearest_remaining_m_ - kProgressStep_m) return;
  nearest_remaining_m_ = remaining_m;
  nearest_remaining_time_s_ = time_s;
}

bool Explorer::without_net_progress(double time_s) const {
  const double timeout_s = params_.explore.net_progress_timeout_s;
  return timeout_s > 0.0 && time_s - nearest_remaining_time_s_ > timeout_s;
}

void Explorer::choose_goal(const ExploreInput& input) {
  map_.compute_reachable(cell_of(input.pose));
  for (int attempt = 0; attempt < kGoalAttemptsPerTick; ++attempt) {
    const Goal goal = goal_value_.select(map_, memory_, input.time_s);
    if (!goal.valid || goal.value <= params_.explore.min_goal_value) {
      // Conclude only from a fresh look: a person who walked past may have left cells that box
      // the robot in or hide the rest, and a look from here re-observes them.
      if (params_.explore.pan_at_goal && !fresh_look_) {
        ++counters_.looks_before_giving_up;
        begin_look(input);
        return;
      }
      if (clear_contacts(input) || lift_shut_gaps(input) || release_blacklist(input) || start_crossing_traces(input) ||
          start_following_trail(input)) {
        map_.compute_reachable(cell_of(input.pose));
        continue;
      }
      finish_exploring(input, FinishReason::explored);
      return;
    }
    ++counters_.goals_chosen;
    goal_ = goal;
    note(ExploreEventKind::goal_chosen, input);
    begin_pursuit(input);
    begin_walker_waits();
    if (replan(input)) {
      state_ = ExploreState::drive;
      return;
    }
    goal_failed(input);
    map_.compute_reachable(cell_of(input.pose));  // the failure may have rebuilt the map
  }
}

void Explorer::finish_exploring(const ExploreInput& input, FinishReason reason) {
  finish_reason_ = reason;
  note(reason == FinishReason::time_limit ? ExploreEventKind::time_limit : ExploreEventKind::explored, input);
  resume_after_look_ = false;
  plan_.clear();
  pan_target_rad_ = 0.0;
  following_trail_ = false;  // the way back follows the trail only when there is no other
  if (!params_.explore.return_to_start) {
    state_ = ExploreState::finished;
    return;
  }
  state_ = ExploreState::returning;
  rebuild(input);  // unknown cells near the start become passable
  goal_ = Goal{};
  goal_.valid = true;
  goal_.position = position_of(start_pose_);
  goal_.cell = map_.grid().cell_of(goal_.position);
  begin_pursuit(input);
  begin_walker_waits();
  if (!replan(input)) goal_failed(input);
}

void Explorer::goal_failed(const ExploreInput& input) {
  plan_.clear();
  stop_last_resorts(input);
  if (state_ == ExploreState::returning) {
    // No way back, or no progress on it: a passer-by may stand in the only door, so look and
    // try again, up to goal_failures_before_blacklist failures in all (a stuck return that
    // replans after every look must end too).
    ++counters_.return_failures;
    note(ExploreEventKind::return_failed, input);
    if (params_.explore.pan_at_goal && counters_.return_failures < static_cast<std::uint64_t>(
                                                                       params_.explore.goal_failures_before_blacklist)) {
      ++counters_.looks_before_giving_up;
      return_after_look_ = true;
      keep_progress_after_look_ = false;
      begin_look(input);
      return;
    }
    state_ = ExploreState::finished;
    return;
  }
  ++counters_.goal_failures;
  note(ExploreEventKind::goal_failed, input);
  if (memory_.record_failure(goal_.position, input.time_s)) {
    counters_.goals_blacklisted = memory_.blacklisted();
    note(ExploreEventKind::goal_blacklisted, input);
  }
  state_ = ExploreState::choose_goal;
}

void Explorer::begin_look(const ExploreInput& input) {
  ++counters_.looks;
  note(ExploreEventKind::look, input);
  state_ = ExploreState::look_around;
  look_step_ = 0;
  look_turned_rad_ = 0.0;
  look_last_heading_ = input.pose.theta;
  look_began_s_ = input.time_s;
}

void Explorer::look_step(const ExploreInput& input, ExploreOutput& output) {
  if (params_.has_pan_unit) {
    pan_target_rad_ = core::degrees_to_radians(kLookTargets_deg[look_step_]);
    if (std::abs(core::wrap_angle(input.pan_rad - pan_target_rad_)) < kPanReached_rad) ++look_step_;
    if (look_step_ == kLookSteps) {
      pan_target_rad_ = 0.0;
      finish_look(input);
      return;
    }
    pan_target_rad_ = core::degrees_to_radians(kLookTargets_deg[look_step_]);
    return;
  }
  look_turned_rad_ += core::wrap_angle(input.pose.theta - look_last_heading_);
  look_last_heading_ = input.pose.theta;
  if (look_turned_rad_ >= 2.0 * core::kPi) {
    finish_look(input);
    return;
  }
  output.drive.angular_rad_s = params_.max_turn_rate_rad_s;
}

void Explorer::finish_look(const ExploreInput& input) {
  fresh_look_ = true;
  // What the look saw still standing near the robot is no person's trace (with
  // trace_confirm_seen_floor, only where it sees the floor; with trace_confirm_before_look,
  // only what was a trace when the look began, not what appeared while it looked). While
  // crossing traces, the map changes with that, and with the traces that aged while the robot
  // stood.
  const double seen_from_m = params_.explore.trace_confirm_seen_floor ? params_.unseen_floor_radius_m() : 0.0;
  const double traces_as_of_s = params_.explore.trace_confirm_before_look ? look_began_s_ : input.time_s;
  counters_.traces_confirmed +=
      traces_.confirm_near(input.grid, position_of(input.pose), seen_from_m, input.time_s, traces_as_of_s);
  if (!return_after_look_ && !resume_after_look_) {
    if (crossing_traces_) rebuild_map(input);
    state_ = ExploreState::choose_goal;
    return;
  }
  // Back to the goal (or the start) of before the look, on a plan made from the new views.
  const ExploreState resumed = return_after_look_ ? ExploreState::returning : ExploreState::drive;
  state_ = resumed;
  return_after_look_ = false;
  resume_after_look_ = false;
  // The rebuild checks the old plan against the new views: it may fail the goal already, and
  // a second try here would count a second failure of the same goal on the same map.
  rebuild(input);
  const bool keep_progress = keep_progress_after_look_;
  keep_progress_after_look_ = false;
  if (state_ != resumed) return;
  if (!keep_progress) begin_pursuit(input);
  if (!replan(input)) goal_failed(input);
}

void Explorer::drive_step(const ExploreInput& input, ExploreOutput& output) {
  if (params_.explore.door_axis_before_m > 0.0) {
    door_axis_.update(plan_, follower_.progress(), map_, position_of(input.pose));
    if (sighting_.holding()) door_axis_.follow_sighting(sighting_.door());
  }
  const FollowResult follow = follower_.follow(plan_, input.pose, door_axis_.passage());
  if (follow.reached) {
    plan_.clear();
    // The gaze's last angle would otherwise stay where nothing asks for another (the end of the
    // return); a look sets its own targets.
    if (gazing()) pan_target_rad_ = 0.0;
    if (state_ == ExploreState::returning) {
      note(ExploreEventKind::returned, input);
      state_ = ExploreState::finished;
      return;
    }
    ++counters_.goals_reached;
    note(ExploreEventKind::goal_reached, input);
    memory_.record_visit(goal_.position);
    stop_last_resorts(input);
    if (params_.explore.pan_at_goal) {
      begin_look(input);
    } else {
      state_ = ExploreState::choose_goal;
    }
    return;
  }
  if (gazing()) pan_target_rad_ = gaze_pan_rad(input.pose);
  const double distance = remaining_path_m(position_of(input.pose));
  if (distance < best_goal_distance_m_ - kProgressStep_m) {
    best_goal_distance_m_ = distance;
    last_progress_time_s_ = input.time_s;
  } else if (input.time_s - last_progress_time_s_ > params_.explore.stuck_timeout_s) {
    ++counters_.stuck;
    note(ExploreEventKind::stuck, input);
    goal_failed(input);
    return;
  }
  if (out_of_time(input.time_s)) {
    ++counters_.goal_timeouts;
    note(ExploreEventKind::goal_timeout, input);
    goal_failed(input);
    return;
  }
  track_net_progress(distance, input.time_s);
  if (without_net_progress(input.time_s)) {
    ++counters_.net_progress_timeouts;
    note(ExploreEventKind::no_net_progress, input);
    goal_failed(input);
    return;
  }
  if (stalled_) {
    // Pushing against something no view showed: keep its cells and plan around them.
    ++counters_.stalls;
    note(ExploreEventKind::stall, input);
    contacts_.record(map_.grid(), input.pose, params_.robot_radius_m, input.time_s, trail_);
    if (params_.explore.stall_back_off_m > 0.0) {
      begin_back_off(input, output, params_.explore.stall_back_off_m);
      return;
    }
    stop_and_look(input, output, 0.0);
    return;
  }
  // A scan hold lasts until the scan that blocked is scan_guard_max_age_s old, whatever later
  // scans show, and the robot does not even turn: a walker who came nearer than the matcher's
  // range is in no later scan, and a turn in place brings an update (the lab, seed 1: a turn
  // 0.1 s into a hold, an update without the walker, and the robot drove into them).
  if (holding_for_scan_ && input.time_s < scan_hold_until_s_) return;
  if (input.time_s < walker_hold_until_s_) return;
  // The current grid, with the contact cells when there are any (stamped at the last rebuild,
  // which follows every grid update).
  const GridView& grid = planning_on_copy_ ? planning_grid_ : input.grid;
  core::DriveCommand command = follow.command;
  centre_in_layer_gap(input, command);
  stand_off(grid, input, command);
  const Blocked blocked = command.linear_mps > 0.0 ? stretch_blocked(grid, input) : Blocked::no;
  if (blocked != Blocked::no && turn_to_face_plan(grid, input, output)) return;
  if (blocked == Blocked::by_scan) {
    hold_for_scan(input);
    return;
  }
  holding_for_scan_ = false;
  if (blocked == Blocked::by_grid) {
    ++counters_.safety_stops;
    note(ExploreEventKind::safety_stop, input);
    if (back_off_to_see(input, output)) return;
    stop_and_look(input, output, command.angular_rad_s);
    return;
  }
  output.drive = command;
}

// A side door seen from the corridor only as the robot turns into it stands too near the camera
// for its jambs to be measured (the dense matcher starts at 0.63 m): looking where the plan
// goes, the camera sees it from before the turn. Within gaze_max_pan_deg of the heading, the
// scan guard still sees what lies straight ahead.
double Explorer::gaze_pan_rad(const core::Pose2& pose) const {
  const Eigen::Vector2d robot = position_of(pose);
  const Eigen::Vector2d to_point = follower_.point_ahead(plan_, robot, params_.explore.gaze_ahead_m) - robot;
  // A waypoint this near gives no direction (only with gaze_ahead_m below it: the goal is reached
  // from goal_tolerance_m).
  if (to_point.squaredNorm() < kAheadCheck_m * kAheadCheck_m) return 0.0;
  const double limit = core::degrees_to_radians(params_.explore.gaze_max_pan_deg);
  return std::clamp(core::wrap_angle(std::atan2(to_point.y(), to_point.x()) - pose.theta), -limit, limit);
}

// The follower steers by the map pose and the plan, both from the estimate's grid; a door's
// jambs kept in the layer lie where the camera saw them relative to the robot, by the odometry
// alone. At office seed 2's contact with N1's west jamb the kept points lay within 0.02 m of
// the jamb while the robot drove 0.11 m off the door's middle into it (docs/results.md).
void Explorer::centre_in_layer_gap(const ExploreInput& input, core::DriveCommand& command) {
  const double reach = params_.explore.layer_gap_reach_m;
  if (reach <= 0.0 || command.linear_mps <= 0.0) return;
  const double radius = params_.robot_radius_m;
  RecentObstacles::Gap gap;
  if (!recent_.gap_ahead(input.pose, input.odometry, radius, kLayerGapAhead_m, radius + reach,
                         std::min(params_.explore.recent_obstacle_min_points, RecentObstacles::kMaxGapSupport), gap)) {
    return;
  }
  const double width = gap.left.y() - gap.right.y();
  if (width < 2.0 * radius || width > 2.0 * (radius + reach) ||
      std::abs(gap.left.x() - gap.right.x()) > kLayerGapSquare_m) {
    return;
  }
  const Eigen::Vector2d side = (gap.left - gap.right).normalized();
  const Eigen::Vector2d left = input.pose.transform_point(gap.left + kLayerGapSlack_m * side);
  const Eigen::Vector2d right = input.pose.transform_point(gap.right - kLayerGapSlack_m * side);
  if (!plan_passes_between(position_of(input.pose), left, right)) return;
  const Eigen::Vector2d middle = 0.5 * (gap.left + gap.right);
  const double aim_ahead = std::max(middle.x(), params_.explore.narrow_lookahead_m > 0.0
                                                    ? params_.explore.narrow_lookahead_m
                                                    : params_.explore.lookahead_m);
  command = pursue(input.pose.transform_point({aim_ahead, middle.y()}), input.pose, params_);
  ++counters_.layer_gap_steers;
}

// The plan, from the robot on for kLayerGapPlan_m, runs across the segment left-right.
bool Explorer::plan_passes_between(const Eigen::Vector2d& robot, const Eigen::Vector2d& left,
                                   const Eigen::Vector2d& right) const {
  double travelled = 0.0;
  Eigen::Vector2d previous = robot;
  for (std::size_t k = follower_.progress(); k < plan_.waypoints.size() && travelled <= kLayerGapPlan_m; ++k) {
    if (segments_meet(previous, plan_.waypoints[k], left, right)) return true;
    travelled += (plan_.waypoints[k] - previous).norm();
    previous = plan_.waypoints[k];
  }
  return false;
}

void Explorer::stand_off(const GridView& grid, const ExploreInput& input, core::DriveCommand& command) {
  if (!standoff_.enabled()) return;
  const DoorPassage& passage = door_axis_.passage();
  const bool sighted = sighting_.holding() && same_door(sighting_.door(), passage);
  DoorStandoff::GridAnswers answers;
  if (passage.known && standoff_.wants_grid(passage)) {
    answers.in_a_wall = DoorSighting::in_a_wall(passage, grid);
    const Eigen::Vector2d to_point = standoff_.point(passage) - position_of(input.pose);
    const double length_m = to_point.norm();
    answers.way_clear =
        length_m == 0.0 || !straight_move_blocked(grid, input, to_point / length_m, 0.0, length_m, false);
  }
  const std::uint64_t stood_off = standoff_.counters().stood_off;
  standoff_.steer(passage, sighted, answers, input.pose, input.time_s, command);
  if (standoff_.counters().stood_off > stood_off) {
    note(ExploreEventKind::door_standoff, input, passage.middle, sighted ? 1.0 : 0.0);
  }
}


// Pure pursuit cuts the plan's corners; beside an obstacle the cut can touch it where the plan
// itself keeps clear (A* checks the disc on the plan's cells only). Before calling the way
// blocked: when the point just ahead towards the plan's next waypoint is clear, turn in place
// to face it (the follower then drives on from a heading along the plan). True while turning.
bool Explorer::turn_to_face_plan(const GridView& grid, const ExploreInput& input, ExploreOutput& output) {
  const core::Pose2& pose = input.pose;
  const Eigen::Vector2d robot = position_of(pose);
  for (std::size_t k = follower_.progress(); k < plan_.waypoints.size(); ++k) {
    const Eigen::Vector2d towards = plan_.waypoints[k] - robot;
    if (towards.norm() < kAheadCheck_m) continue;
    const double heading_error = core::wrap_angle(std::atan2(towards.y(), towards.x()) - pose.theta);
    if (std::abs(heading_error) < kFacingPlan_rad) return false;  // already facing it: blocked
    if (disc_blocked(grid, robot + kAheadCheck_m * towards.normalized(), robot, input) != Blocked::no) return false;
    output.drive.angular_rad_s = std::copysign(params_.max_turn_rate_rad_s, heading_error);
    ++counters_.turns_to_face_plan;
    return true;
  }
  return false;
}

// What the scan guard saw is most likely a walker crossing: the robot stands still, without a
// look (a 13 s look kept it standing in the walker's lane, and their passing cells boxed it
// in: the lab, seed 2). A standing robot makes no update, so the hold ends when the scan is
// scan_guard_max_age_s old; the next update, 0.07 m on, stops it again if they are still there.
void Explorer::hold_for_scan(const ExploreInput& input) {
  scan_hold_until_s_ = std::max(scan_hold_until_s_, input.seen.time_s + params_.explore.scan_guard_max_age_s);
  if (holding_for_scan_) return;
  holding_for_scan_ = true;
  ++counters_.scan_guard_stops;
  note(ExploreEventKind::scan_stop, input);
}

// Stops, and replans from a rebuilt map on the next tick. With pan_at_goal it looks around
// first: a robot standing still makes no observation update (they follow motion), so what
// blocks it would never be looked at again (a person who has walked on is cleared by the
// look's views); then it carries on to the same goal (or the start) on a new plan. Without a
// pan unit it turns in place at `turn_rad_s`, which moves the disc into no new cell and lets
// it face a replanned path (or a cleared view) instead of standing still for ever.
void Explorer::stop_and_look(const ExploreInput& input, ExploreOutput& output, double turn_rad_s) {
  rebuild_needed_ = true;
  if (params_.explore.pan_at_goal) {
    if (state_ == ExploreState::returning) {
      return_after_look_ = true;
    } else {
      resume_after_look_ = true;
    }
    keep_progress_after_look_ = true;  // a goal blocked for stuck_timeout_s still fails
    begin_look(input);
    return;
  }
  output.drive.angular_rad_s = turn_rad_s;
}

// Straight back at top speed, while the disc just behind is clear in the planning grid (the
// camera looks ahead, so the grid is all there is to go by), until stall_back_off_m is covered
// or twice the time it needs has passed (something behind that no view showed).
// When the way straight back is shut from the start, the robot first turns in place (a disc
// that turns moves into no new cell) to the nearest heading within stall_back_off_turn_deg
// whose way back is clear for at least kBackOffLeastFraction of it: in a door the estimate put
// off its middle, a jamb's cell behind refused every back-off, and a robot that does not move
// makes no update that could change that (office seed 1 with the random walk: 1340 s at a
// jamb, 827 back-offs refused).
void Explorer::begin_back_off(const ExploreInput& input, ExploreOutput& output, double distance_m) {
  ++counters_.back_offs;
  backing_off_ = true;
  back_off_m_ = distance_m;
  back_off_from_ = position_of(input.pose);
  back_off_start_s_ = input.time_s;
  back_off_turning_ = false;
  if (back_off_blocked(input, input.pose.theta, kAheadCheck_m)) choose_back_off_heading(input);
  back_off_step(input, output);
}

// A safety stop while crossing traces, with a trace ahead where the camera sees no floor (a
// person who walked past right in front of the robot, in a door): a look from here could neither
// clear it nor tell it from an obstacle, and the plan would cross it again after the look. So
// the robot first backs off until it lies a cell beyond that, by the grid behind (the
// back-off ends with the look). With explore.trace_confirm_seen_floor, and only when
// stall_back_off_m allows backing off at all.
bool Explorer::back_off_to_see(const ExploreInput& input, ExploreOutput& output) {
  if (!crossing_traces_ || !params_.explore.trace_confirm_seen_floor || params_.explore.stall_back_off_m <= 0.0) {
    return false;
  }
  const double unseen_m = params_.unseen_floor_radius_m();
  if (!std::isfinite(unseen_m)) return false;  // a camera that never sees the floor
  const double nearest_m = traces_.nearest_trace_ahead_m(input.grid, position_of(input.pose),
                                                         unit_towards(input.pose.theta), unseen_m, input.time_s);
  if (nearest_m >= unseen_m) return false;
  ++counters_.back_offs_to_see;
  note(ExploreEventKind::backing_to_see, input);
  begin_back_off(input, output, unseen_m - nearest_m + input.grid.resolution_m);
  return true;
}

// True when the disc, backed straight off along heading_rad from where the robot stands,
// touches something in the planning grid (or the latest scan) anywhere from kAheadCheck_m to
// reach_m behind: kAheadCheck_m is each tick's check, and kAheadCheck_m + a distance covers
// the checks of a back-off that far.
bool Explorer::back_off_blocked(const ExploreInput& input, double heading_rad, double reach_m) const {
  const GridView& grid = planning_on_copy_ ? planning_grid_ : input.grid;
  return straight_move_blocked(grid, input, -unit_towards(heading_rad), kAheadCheck_m, reach_m, true);
}

// True when the disc, moved straight from where the robot stands along `direction` (a unit
// vector), touches an occupied cell of `grid` (with `scan_too`, or what the scan guard holds in
// the latest scan) anywhere from `from_m` to `to_m` (every kBackOffCheckStep_cells, and at to_m).
bool Explorer::straight_move_blocked(const GridView& grid, const ExploreInput& input, const Eigen::Vector2d& direction,
                                     double from_m, double to_m, bool scan_too) const {
  const Eigen::Vector2d robot = position_of(input.pose);
  const double step_m = kBackOffCheckStep_cells * grid.resolution_m;
  for (double along_m = from_m;; along_m += step_m) {
    along_m = std::min(along_m, to_m);
    const Eigen::Vector2d centre = robot + along_m * direction;
    const bool blocked = scan_too ? disc_blocked(grid, centre, robot, input) != Blocked::no
                                  : grid_blocks_disc(grid, centre, robot, input.time_s);
    if (blocked) return true;
    if (along_m >= to_m) return false;
  }
}

double Explorer::least_back_off_reach_m() const {
  return kAheadCheck_m + kBackOffLeastFraction * back_off_m_;
}

// The nearest turn first, to the left before the right; none when every one is shut too.
void Explorer::choose_back_off_heading(const ExploreInput& input) {
  const double step_rad = core::degrees_to_radians(kBackOffTurnStep_deg);
  const double widest_rad = core::degrees_to_radians(params_.explore.stall_back_off_turn_deg);
  for (double turn_rad = step_rad; turn_rad <= widest_rad + 1e-9; turn_rad += step_rad) {
    for (const double side : {1.0, -1.0}) {
      const double heading_rad = core::wrap_angle(input.pose.theta + side * turn_rad);
      if (back_off_blocked(input, heading_rad, least_back_off_reach_m())) continue;
      back_off_turning_ = true;
      back_off_heading_rad_ = heading_rad;
      back_off_turn_until_s_ = input.time_s + 2.0 * turn_rad / params_.max_turn_rate_rad_s;
      ++counters_.back_off_turns;
      return;
    }
  }
}

// False when done (then backing_off_ is cleared).
bool Explorer::back_off_step(const ExploreInput& input, ExploreOutput& output) {
  const Eigen::Vector2d robot = position_of(input.pose);
  if (back_off_turning_) {
    // Until the way back is clear enough from the heading reached: the chosen one was so from
    // the pose estimate at the start, and the turn ends within kFacingPlan_rad of it.
    const double error_rad = core::wrap_angle(back_off_heading_rad_ - input.pose.theta);
    const bool turning = std::abs(error_rad) >= kFacingPlan_rad && input.time_s <= back_off_turn_until_s_ &&
                         back_off_blocked(input, input.pose.theta, least_back_off_reach_m());
    if (turning) {
      output.drive.angular_rad_s = std::copysign(params_.max_turn_rate_rad_s, error_rad);
      return true;
    }
    back_off_turning_ = false;  // the straight part starts here
    back_off_from_ = robot;
    back_off_start_s_ = input.time_s;
  }
  const double distance = back_off_m_;
  const bool done = (robot - back_off_from_).norm() >= distance ||
                    input.time_s - back_off_start_s_ > 2.0 * distance / params_.max_speed_mps ||
                    back_off_blocked(input, input.pose.theta, kAheadCheck_m);
  if (done) {
    backing_off_ = false;
    return false;
  }
  output.drive.linear_mps = -params_.max_speed_mps;
  return true;
}

Explorer::Blocked Explorer::disc_blocked(const GridView& grid, const Eigen::Vector2d& centre,
                                         const Eigen::Vector2d& robot, const ExploreInput& input) const {
  if (grid_blocks_disc(grid, centre, robot, input.time_s)) return Blocked::by_grid;
  if (scan_guard_active(input) && scan_blocks_disc(input.seen, centre, robot)) return Blocked::by_scan;
  return Blocked::no;
}

bool Explorer::grid_blocks_disc(const GridView& grid, const Eigen::Vector2d& centre, const Eigen::Vector2d& robot,
                                double time_s) const {
  const double deep = std::max(0.0, params_.robot_radius_m - grid.resolution_m);
  const double widest = params_.robot_radius_m + std::max(0.0, traces_.margin_m());
  const int reach = static_cast<int>(std::ceil(widest / grid.resolution_m)) + 1;
  const Eigen::Vector2i middle = grid.cell_of(centre);
  for (int y = middle.y() - reach; y <= middle.y() + reach; ++y) {
    for (int x = middle.x() - reach; x <= middle.x() + reach; ++x) {
      if (!grid.contains(x, y) || grid.at(x, y) != CellState::occupied) continue;
      const double radius = params_.robot_radius_m + (traces_.fresh(grid, x, y, time_s) ? traces_.margin_m() : 0.0);
      if (move_touches(grid.center(x, y), centre, robot, radius, deep)) return true;
    }
  }
  return false;
}

bool Explorer::scan_guard_active(const ExploreInput& input) const {
  return params_.explore.scan_guard_min_points > 0 && input.seen.count > 0 &&
         input.time_s - input.seen.time_s <= params_.explore.scan_guard_max_age_s;
}

// The latest scan's obstacles at camera height: scan_guard_min_points of them inside the disc,
// so that stray matches do not stop the robot. They are measured from the robot, so one inside
// the disc along the plan is a real obstacle closer than the robot's radius to where it will
// be, whatever the grid holds there (a walking person's lane is often occupied in it).
bool Explorer::scan_blocks_disc(const SeenObstacles& seen, const Eigen::Vector2d& centre,
                                const Eigen::Vector2d& robot) const {
  const double radius = params_.robot_radius_m;
  const double deep = std::max(0.0, radius - kScanGuardDeep_m);
  int inside = 0;
  for (std::size_t i = 0; i < seen.count; ++i) {
    const Eigen::Vector2d point = seen_correction_.transform_point(seen.points[i]);
    if (move_touches(point, centre, robot, radius, deep) && ++inside >= params_.explore.scan_guard_min_points) {
      return true;
    }
  }
  return false;
}

// The scan guard looks farther than the grid's check, along the plan and along the heading
// (pure pursuit cuts the plan's corners) but not past the plan's end (a goal faces a wall at
// its safe distance): the matcher sees nothing within 0.73 m of the robot's centre, and a
// walker closes 0.3-0.9 m between two updates.
bool Explorer::scan_blocks_stretch(const ExploreInput& input) const {
  const Eigen::Vector2d robot = position_of(input.pose);
  const Eigen::Vector2d heading(std::cos(input.pose.theta), std::sin(input.pose.theta));
  const double reach = params_.explore.scan_guard_distance_m;
  const double heading_reach = std::min(reach, remaining_path_m(robot));
  for (double ahead = kAheadCheck_m; ahead <= heading_reach + 1e-9; ahead += kAheadCheck_m) {
    if (scan_blocks_disc(input.seen, robot + ahead * heading, robot)) return true;
  }
  double travelled = 0.0;
  Eigen::Vector2d previous = robot;
  for (std::size_t k = follower_.progress(); k < plan_.waypoints.size(); ++k) {
    travelled += (plan_.waypoints[k] - previous).norm();
    previous = plan_.waypoints[k];
    if (travelled > reach) break;
    if ((plan_.waypoints[k] - robot).norm() < kAheadCheck_m) continue;
    if (scan_blocks_disc(input.seen, plan_.waypoints[k], robot)) return true;
  }
  return false;
}

Explorer::Blocked Explorer::stretch_blocked(const GridView& grid, const ExploreInput& input) const {
  const Eigen::Vector2d robot = position_of(input.pose);
  const Eigen::Vector2d ahead = robot + kAheadCheck_m * unit_towards(input.pose.theta);
  if (grid_blocks_disc(grid, ahead, robot, input.time_s)) return Blocked::by_grid;
  double travelled = 0.0;
  Eigen::Vector2d previous = robot;
  for (std::size_t k = follower_.progress(); k < plan_.waypoints.size(); ++k) {
    travelled += (plan_.waypoints[k] - previous).norm();
    previous = plan_.waypoints[k];
    if (travelled > params_.explore.safety_check_distance_m) break;
    // A waypoint this near is where the robot stands (the centre of its own cell), no move:
    // the point ahead stands for it.
    if ((plan_.waypoints[k] - robot).norm() < kAheadCheck_m) continue;
    if (grid_blocks_disc(grid, plan_.waypoints[k], robot, input.time_s)) return Blocked::by_grid;
  }
  if (scan_guard_active(input) && scan_blocks_stretch(input)) return Blocked::by_scan;
  return Blocked::no;
}

}  // namespace stereoscout::explore
