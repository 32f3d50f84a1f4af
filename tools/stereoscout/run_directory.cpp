#include "run_directory.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "map_eval.hpp"
#include "map_png.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/host_sim/ground_truth.hpp"
#include "stereoscout/occupancy/final_map.hpp"
#include "stereoscout/occupancy/ros_map.hpp"
#include "stereoscout/report/json_writer.hpp"
#include "stereoscout/report/sha256.hpp"
#include "stereoscout/slam/slam_export.hpp"

namespace stereoscout::cli {
namespace {

bool write_text(const std::string& path, const std::string& text, std::string& error) {
  std::ofstream file(path, std::ios::binary);
  file << text;
  if (!file.good()) error = path + ": cannot write";
  return file.good();
}

// The ML particle's trajectory, root first: update index -> pose.
std::map<std::uint32_t, core::Pose2> ml_trajectory(const slam::ParticleFilter& filter) {
  std::map<std::uint32_t, core::Pose2> poses;
  const slam::TrajectoryTree& tree = filter.trajectory();
  for (slam::TrajectoryNodeHandle n = filter.ml_trajectory_node(); n; n = tree.parent(n)) {
    poses[tree.get(n).update_index] = tree.get(n).pose;
  }
  return poses;
}

// Root-mean-square position error against the true poses of the updates. The map frame is
// the odometry frame at start, which the simulator puts at the true start pose, so no
// alignment is fitted: a constant offset counts as error.
void score_trajectories(const stack::Stack& stack, RunScore& score) {
  const std::map<std::uint32_t, core::Pose2> estimate = ml_trajectory(stack.filter());
  double filter_sum = 0.0;
  double odometry_sum = 0.0;
  std::size_t count = 0;
  for (const stack::UpdateRecord& record : stack.update_records()) {
    if (!record.has_ground_truth) return;
    const auto it = estimate.find(record.update_index);
    if (it == estimate.end()) continue;
    filter_sum += (it->second.translation() - record.ground_truth.translation()).squaredNorm();
    odometry_sum += (record.odometry.translation() - record.ground_truth.translation()).squaredNorm();
    ++count;
  }
  if (count == 0) return;
  score.ate_rmse_m = std::sqrt(filter_sum / static_cast<double>(count));
  score.odometry_ate_rmse_m = std::sqrt(odometry_sum / static_cast<double>(count));
}

occupancy::RosMap ros_map_of(const host_sim::GroundTruthGrid& grid) {
  occupancy::RosMap map;
  map.geometry.width_cells = grid.width;
  map.geometry.height_cells = grid.height;
  map.geometry.resolution_m = grid.resolution_m;
  map.geometry.origin_x_m = grid.origin.x();
  map.geometry.origin_y_m = grid.origin.y();
  map.cells.resize(grid.cells.size());
  for (std::size_t i = 0; i < grid.cells.size(); ++i) {
    map.cells[i] = grid.cells[i] == host_sim::GroundTruthGrid::free       ? occupancy::CellState::free
                   : grid.cells[i] == host_sim::GroundTruthGrid::occupied ? occupancy::CellState::occupied
                                                                          : occupancy::CellState::unknown;
  }
  return map;
}

// Scored on the navigation grid the robot explored with (the ML grid at grid.resolution_m,
// the ground truth's resolution, holding every scan of the ML trajectory), not on the 1 cm
// final map: there, cells between two rays stay unknown at a distance, which would count
// against coverage although the robot has seen the space.
void score_map(const stack::Stack& stack, const core::SystemConfig& config, const RunContext& context,
               RunScore& score) {
  const occupancy::OccupancyGrid* grid = stack.grid().ml_grid();
  if (context.world == nullptr || grid == nullptr) return;
  const occupancy::RosMap map = occupancy::classify_grid(*grid, occupancy::CellThresholds::from_config(config.grid));
  const host_sim::GroundTruthGrid truth = host_sim::rasterize_world(
      *context.world, config.grid.resolution_m, config.sim.floor_tolerance_m, config.robot.height_m);
  const host_sim::GroundTruthGrid reachable =
      host_sim::reachable_free_space(truth, context.world->start.translation(), config.robot.radius_m);
  const occupancy::RosMap truth_map = ros_map_of(truth);
  const occupancy::RosMap reachable_map = ros_map_of(reachable);
  const MapEvaluation evaluation = evaluate_map(map, truth_map, &reachable_map);
  score.coverage = evaluation.coverage();
  score.map_agreement = evaluation.accuracy();
}

// groundtruth.tum is written when every update knows its true pose (simulated runs).
bool every_update_has_truth(const stack::Stack& stack) {
  const auto& records = stack.update_records();
  return !records.empty() &&
         std::all_of(records.begin(), records.end(), [](const stack::UpdateRecord& r) { return r.has_ground_truth; });
}

std::string write_trajectories(const stack::Stack& stack, const std::string& out, std::string& error) {
  std::ostringstream trajectory;
  slam::write_tum_trajectory(trajectory, stack.filter().trajectory(), stack.filter().ml_trajectory_node());
  std::ostringstream odometry;
  std::ostringstream truth;
  const bool has_truth = every_update_has_truth(stack);
  for (const stack::UpdateRecord& record : stack.update_records()) {
    odometry << slam::tum_line(record.timestamp_ns, record.odometry);
    if (has_truth) truth << slam::tum_line(record.timestamp_ns, record.ground_truth);
  }
  if (!write_text(out + "/trajectory.tum", trajectory.str(), error)) return error;
  if (!write_text(out + "/odometry.tum", odometry.str(), error)) return error;
  if (has_truth && !write_text(out + "/groundtruth.tum", truth.str(), error)) return error;
  return {};
}

std::string write_maps(const stack::Stack& stack, const core::SystemConfig& config, const std::string& out,
                       occupancy::RosMap& map, occupancy::TrajectoryScanCounts& counts) {
  const std::unique_ptr<occupancy::OccupancyGrid> grid = occupancy::build_final_map(
      stack.filter().trajectory(), stack.filter().ml_trajectory_node(), stack.grid().scans(), &stack.scan_archive(),
      config.grid.final_map_resolution_m, config.grid.final_map_margin_m, occupancy::LogOddsModel::from_config(config.grid), &counts);
  map = occupancy::classify_grid(*grid, occupancy::CellThresholds::from_config(config.grid));
  std::string error = occupancy::write_ros_map(map, out + "/map.pgm", out + "/map.yaml");
  if (!error.empty()) return error;
  return write_map_png(map, map_overlays(stack), out + "/map.png");
}

// The explorer's journal, oldest event first (docs/report.md, "explore_events.csv").
std::string explore_events_csv(const explore::ExploreJournal& journal) {
  std::string text = "time_s,event,x_m,y_m,theta_rad,goal_x_m,goal_y_m,goal_value\n";
  char line[160];
  for (std::size_t i = 0; i < journal.size(); ++i) {
    const explore::ExploreEvent& e = journal[i];
    std::snprintf(line, sizeof line, "%.2f,%s,%.3f,%.3f,%.4f,%.3f,%.3f,%.2f\n", e.time_s, explore::to_string(e.kind),
                  e.pose.x, e.pose.y, e.pose.theta, e.goal.x(), e.goal.y(), e.goal_value);
    text += line;
  }
  return text;
}

void write_timing(report::JsonWriter& json, const scheduler::Scheduler& scheduler) {
  json.begin_object("timing");
  for (std::size_t i = 0; i < scheduler.task_count(); ++i) {
    const scheduler::TaskStats task = scheduler.stats(i);
    json.begin_object(task.name)
        .unsigned_integer("runs", task.runs)
        .integer("budget_us", task.budget_us)
        .integer("median_us", task.median_us)
        .integer("p99_us", task.p99_us)
        .integer("max_us", task.max_us)
        .unsigned_integer("overruns", task.overruns)
        .unsigned_integer("deferred", task.deferred)
        .unsigned_integer("missed_periods", task.missed_periods)
        .unsigned_integer("failures", task.failures)
        .end_object();
  }
  json.end_object();
}

void pool(report::JsonWriter& json, const char* name, std::size_t capacity, std::size_t high_water,
          std::uint64_t exhausted) {
  json.begin_object(name)
      .unsigned_integer("capacity", capacity)
      .unsigned_integer("high_water", high_water)
      .unsigned_integer("exhausted", exhausted)
      .end_object();
}

void write_pools(report::JsonWriter& json, const stack::Stack& stack, const core::SystemConfig& config) {
  const slam::ParticleFilter& filter = stack.filter();
  const core::PoolStats nodes = filter.landmarks().node_stats();
  const core::PoolStats estimates = filter.landmarks().estimate_stats();
  const core::PoolStats trajectory = filter.trajectory().stats();
  const occupancy::JustInTimeGridStats& grid = stack.grid().stats();
  const vision::DescriptorIndexStats& index = stack.vision().index().stats();
  const std::uint64_t scans = stack.update_records().size();
  const auto ring = static_cast<std::uint64_t>(config.grid.scan_history);
  json.begin_object("pools");
  pool(json, "particles", static_cast<std::size_t>(filter.config().particle_capacity), filter.particle_count(), 0);
  pool(json, "landmark_nodes", nodes.capacity, nodes.high_water, nodes.exhausted);
  pool(json, "landmark_estimates", estimates.capacity, estimates.high_water, estimates.exhausted);
  pool(json, "trajectory_nodes", trajectory.capacity, trajectory.high_water, trajectory.exhausted);
  pool(json, "grid_cache", stack.grid().cache_capacity(), static_cast<std::size_t>(grid.grids_held_max), grid.evictions);
  pool(json, "scan_history", static_cast<std::size_t>(ring), static_cast<std::size_t>(std::min(scans, ring)),
       scans > ring ? scans - ring : 0);
  pool(json, "descriptor_index", index.capacity, index.entries, index.refused);
  const occupancy::ScanArchiveStats& archive = stack.scan_archive().stats();
  pool(json, "final_map_tiles", stack.scan_archive().tile_capacity(), archive.tiles_used, archive.tile_refusals);
  json.end_object();
}

// Where map.pgm's scans came from (docs/report.md, "final_map").
void write_final_map(report::JsonWriter& json, const occupancy::TrajectoryScanCounts& counts,
                     const occupancy::ScanArchiveStats& archive) {
  json.begin_object("final_map")
      .unsigned_integer("trajectory_nodes", counts.nodes)
      .unsigned_integer("scans_from_ring", counts.scans_inserted)
      .unsigned_integer("nodes_before_ring", counts.nodes_archived)
      .unsigned_integer("scans_archived", archive.scans_archived)
      .unsigned_integer("scans_missing", counts.scans_overwritten)
      .boolean("archive_on_final_lineage", counts.archive_on_lineage)
      .unsigned_integer("archive_lineage_switches", archive.lineage_switches)
      .unsigned_integer("archive_scans_off_lineage", archive.scans_off_lineage)
      .unsigned_integer("archive_scans_outside", archive.scans_outside)
      .end_object();
}

// The front end's identities against the truth: null where the run has none (the robot).
void write_identity_check(report::JsonWriter& json, const vision::IdentityCheck* check) {
  if (check == nullptr) {
    json.null("reobservation_consistency").null("identity_check");
    return;
  }
  json.number("reobservation_consistency", check->consistency())
      .begin_object("identity_check")
      .unsigned_integer("first_sightings", check->first_sightings())
      .unsigned_integer("reobservations", check->reobservations())
      .unsigned_integer("consistent", check->consistent())
      .unsigned_integer("past_capacity", check->past_capacity())
      .unsigned_integer("floor_reobservations", check->floor_reobservations())
      .unsigned_integer("floor_consistent", check->floor_consistent())
      .end_object();
}

// vision.identity_gate's counts: null when it is off.
void write_identity_gate(report::JsonWriter& json, const vision::IdentityGate* gate) {
  if (gate == nullptr) {
    json.null("identity_gate");
    return;
  }
  const vision::IdentityGateStats& s = gate->stats();
  json.begin_object("identity_gate")
      .unsigned_integer("observations", s.observations)
      .unsigned_integer("joined", s.joined)
      .unsigned_integer("instances_created", s.instances_created)
      .unsigned_integer("split", s.split)
      .unsigned_integer("dropped_identity_full", s.dropped_identity_full)
      .unsigned_integer("dropped_pool_full", s.dropped_pool_full)
      .unsigned_integer("dropped_unknown_identity", s.dropped_unknown_identity)
      .end_object();
}

void write_counters(report::JsonWriter& json, const stack::Stack& stack) {
  const stack::StackCounters& c = stack.counters();
  json.begin_object("stack")
      .unsigned_integer("ticks", c.ticks)
      .unsigned_integer("frames_captured", c.frames_captured)
      .unsigned_integer("frames_kept", c.frames_kept)
      .unsigned_integer("frames_skipped_busy", c.frames_skipped_busy)
      .unsigned_integer("frames_expired", c.frames_expired)
      .unsigned_integer("capture_failures", c.capture_failures)
      .unsigned_integer("odometry_readings", c.odometry_readings)
      .unsigned_integer("odometry_rejected", c.odometry_rejected)
      .unsigned_integer("updates_refused", c.updates_refused)
      .unsigned_integer("vision_failures", c.vision_failures)
      .unsigned_integer("near_obstacle_columns", c.near_obstacle_columns)
      .unsigned_integer("rollups", c.rollups)
      .unsigned_integer("replan_steps", c.replans)
      .unsigned_integer("drive_commands", c.drive_commands)
      .unsigned_integer("emergency_stop_ticks", c.emergency_stop_ticks)
      .unsigned_integer("log_records_staged", c.log_records_staged)
      .unsigned_integer("log_stage_overflow", c.log_stage_overflow)
      .unsigned_integer("log_records_refused", c.log_records_refused)
      .unsigned_integer("heap_allocations_in_sift", c.heap_allocations_in_sift)
      .end_object();
  const explore::ExploreCounters& e = stack.explorer().counters();
  const explore::DoorSightingCounters& d = stack.explorer().door_sighting().counters();
  const explore::DoorStandoffCounters& o = stack.explorer().door_standoff().counters();
  json.begin_object("explorer")
      .text("state", explore::to_string(stack.explorer().state()))
      .unsigned_integer("goals_chosen", e.goals_chosen)
      .unsigned_integer("goals_reached", e.goals_reached)
      .unsigned_integer("goals_abandoned", e.goals_abandoned)
      .unsigned_integer("goal_failures", e.goal_failures)
      .unsigned_integer("goals_blacklisted", e.goals_blacklisted)
      .unsigned_integer("plan_failures", e.plan_failures)
      .unsigned_integer("replans", e.replans)
      .unsigned_integer("goal_shifts", e.goal_shifts)
      .unsigned_integer("stuck", e.stuck)
      .unsigned_integer("goal_timeouts", e.goal_timeouts)
      .unsigned_integer("net_progress_timeouts", e.net_progress_timeouts)
      .unsigned_integer("blocked_plan_limits", e.blocked_plan_limits)
      .unsigned_integer("plan_reversals", e.plan_reversals)
      .unsigned_integer("reversal_limits", e.reversal_limits)
      .unsigned_integer("safety_stops", e.safety_stops)
      .unsigned_integer("scan_guard_stops", e.scan_guard_stops)
      .unsigned_integer("turns_to_face_plan", e.turns_to_face_plan)
      .unsigned_integer("layer_gap_steers", e.layer_gap_steers)
      .unsigned_integer("stalls", e.stalls)
      .unsigned_integer("back_offs", e.back_offs)
      .unsigned_integer("back_off_turns", e.back_off_turns)
      .unsigned_integer("contact_cells_recorded", stack.explorer().contacts().recorded())
      .unsigned_integer("contact_cells_held", stack.explorer().contacts().held())
      .unsigned_integer("contact_cells_repeated", stack.explorer().contacts().repeated())
      .unsigned_integer("contact_cells_on_trail", stack.explorer().contacts().on_trail())
      .unsigned_integer("contact_cells_explained", stack.explorer().contacts().explained())
      .unsigned_integer("contact_stalls_toward_mapped", stack.explorer().contacts().toward_mapped())
      .unsigned_integer("contact_clears", e.contact_clears)
      .unsigned_integer("blacklist_releases", e.blacklist_releases)
      .unsigned_integer("gaps_shut", stack.explorer().shut_gaps().gaps_shut())
      .unsigned_integer("shut_gap_cells", stack.explorer().shut_gaps().cells_shut())
      .unsigned_integer("shut_gap_cells_held", stack.explorer().shut_gaps().held())
      .unsigned_integer("shut_gaps_refused_driven", stack.explorer().shut_gaps().refused_driven())
      .unsigned_integer("shut_gaps_refused_far", stack.explorer().shut_gaps().refused_far())
      .unsigned_integer("shut_gap_cells_dropped_full", stack.explorer().shut_gaps().dropped_full())
      .unsigned_integer("shut_gap_driven_restarts", stack.explorer().shut_gaps().driven_restarts())
      .unsigned_integer("shut_gap_lifts", e.shut_gap_lifts)
      .unsigned_integer("recent_points_kept", stack.explorer().recent_obstacles().kept())
      .unsigned_integer("recent_points_seen_past", stack.explorer().recent_obstacles().seen_past())
      .unsigned_integer("recent_points_dropped_full", stack.explorer().recent_obstacles().dropped_full())
      .unsigned_integer("recent_cells_stamped", stack.explorer().recent_obstacles().cells_stamped())
      .unsigned_integer("recent_blank_points_unconfirmed", stack.explorer().recent_obstacles().blank_unconfirmed())
      .unsigned_integer("trace_crossings", e.trace_crossings)
      .unsigned_integer("trail_follows", e.trail_follows)
      .unsigned_integer("traces_confirmed", e.traces_confirmed)
      .unsigned_integer("back_offs_to_see", e.back_offs_to_see)
      .unsigned_integer("traces_seen_standing", e.traces_seen_standing)
      .unsigned_integer("plans_kept_for_walkers", e.plans_kept_for_walkers)
      .unsigned_integer("walker_holds", e.walker_holds)
      .unsigned_integer("plans_switched", e.plans_switched)
      .unsigned_integer("walker_waits_ended", e.walker_waits_ended)
      .unsigned_integer("looks", e.looks)
      .unsigned_integer("door_scans", d.scans_at_doors)
      .unsigned_integer("door_sightings", d.sightings)
      .unsigned_integer("doors_sighted", d.doors_sighted)
      .unsigned_integer("door_not_in_a_wall", d.not_in_a_wall)
      .unsigned_integer("door_no_gap", d.no_gap)
      .unsigned_integer("door_jamb_at_image_edge", d.jamb_at_image_edge)
      .unsigned_integer("door_width_disagrees", d.width_disagrees)
      .unsigned_integer("door_offset_too_large", d.offset_too_large)
      .unsigned_integer("door_headings_corrected", d.headings_corrected)
      .unsigned_integer("door_headings_carried", d.headings_carried)
      .unsigned_integer("door_heading_unmeasured", d.heading_unmeasured)
      .unsigned_integer("door_heading_jumps", d.heading_jumps)
      .unsigned_integer("door_standoff_doors", o.doors)
      .unsigned_integer("door_standoffs", o.stood_off)
      .unsigned_integer("door_standoff_sighted", o.sighted)
      .unsigned_integer("door_standoff_not_in_a_wall", o.not_in_a_wall)
      .unsigned_integer("door_standoff_too_near", o.too_near)
      .unsigned_integer("door_standoff_way_shut", o.way_shut)
      .unsigned_integer("door_standoff_timed_out", o.timed_out)
      .unsigned_integer("events_recorded", stack.explorer().journal().recorded())
      .unsigned_integer("events_dropped", stack.explorer().journal().dropped())
      .end_object();
  const slam::FilterCounters& f = stack.filter().counters();
  json.begin_object("filter")
      .unsigned_integer("observations_used", f.observations_used)
      .unsigned_integer("observations_invalid", f.observations_invalid)
      .unsigned_integer("estimates_added", f.estimates_added)
      .unsigned_integer("estimates_refused_list_full", f.estimates_refused_list_full)
      .unsigned_integer("changes_refused_pool_full", f.changes_refused_pool_full)
      .unsigned_integer("updates_refused_trajectory_full", f.updates_refused_trajectory_full)
      .unsigned_integer("estimate_lineage_switches", f.estimate_lineage_switches)
      .unsigned_integer("estimate_switch_depth_sum", f.estimate_switch_depth_sum)
      .unsigned_integer("estimate_switch_depth_max", f.estimate_switch_depth_max)
      .unsigned_integer("manhattan_walls_learnt", f.manhattan_walls_learnt)
      .unsigned_integer("manhattan_walls_used", f.manhattan_walls_used)
      .unsigned_integer("manhattan_walls_off_axes", f.manhattan_walls_off_axes)
      .boolean("manhattan_axes_fixed", stack.filter().manhattan_frame().fixed())
      .number("manhattan_axis_deg", core::radians_to_degrees(stack.filter().manhattan_frame().axis_rad()))
      .unsigned_integer("manhattan_restarts", stack.filter().manhattan_frame().restarts())
      .end_object();
}

// The first sampled time the navigation grid covered 90% / 95% (null: never), and the curve.
void write_coverage_curve(report::JsonWriter& json, const std::vector<std::pair<double, double>>& curve) {
  if (curve.empty()) return;
  for (const auto& [level, key] : {std::pair<double, const char*>{0.90, "time_to_90_s"}, {0.95, "time_to_95_s"}}) {
    const auto reached = std::find_if(curve.begin(), curve.end(), [l = level](const auto& s) { return s.second >= l; });
    if (reached == curve.end()) {
      json.null(key);
    } else {
      json.number(key, reached->first);
    }
  }
  json.begin_array("coverage_curve");
  for (const auto& [time_s, coverage] : curve) json.begin_array().number(nullptr, time_s).number(nullptr, coverage).end_array();
  json.end_array();
}

void optional_number(report::JsonWriter& json, const char* key, double value) {
  if (value < 0.0) {
    json.null(key);
  } else {
    json.number(key, value);
  }
}

// An array of rows of numbers (the collision and near-miss logs).
template <std::size_t N>
void number_rows(report::JsonWriter& json, const char* key, const std::vector<std::array<double, N>>& rows) {
  json.begin_array(key);
  for (const auto& row : rows) {
    json.begin_array();
    for (const double value : row) json.number(nullptr, value);
    json.end_array();
  }
  json.end_array();
}

// The door visits' counts, the 10th percentile and the median of the logged visits' least
// clearances (null without a visit), and the log.
void write_door_visits(report::JsonWriter& json, const RunContext& context) {
  json.number("door_visit_reach_m", context.door_visit_reach_m)
      .unsigned_integer("door_visits", context.door_visits)
      .unsigned_integer("door_crossings", context.door_crossings)
      .unsigned_integer("door_visits_touched", context.door_visits_touched);
  std::vector<double> clearances;
  for (const auto& visit : context.door_visit_log) clearances.push_back(visit[4]);
  std::sort(clearances.begin(), clearances.end());
  const auto quantile = [&clearances](double q) {
    return clearances[static_cast<std::size_t>(q * static_cast<double>(clearances.size() - 1) + 0.5)];
  };
  if (clearances.empty()) {
    json.null("door_clearance_p10_m").null("door_clearance_median_m");
  } else {
    json.number("door_clearance_p10_m", quantile(0.1)).number("door_clearance_median_m", quantile(0.5));
  }
  number_rows(json, "door_visit_log", context.door_visit_log);
}

std::string report_json(const stack::Stack& stack, const core::SystemConfig& config, const RunContext& context,
                        const RunScore& score, const std::map<std::string, std::string>& digests) {
  const occupancy::JustInTimeGridStats& grid = stack.grid().stats();
  report::JsonWriter json;
  json.begin_object()
      .text("command", context.command)
      .text("world", context.world_name)
      .integer("seed", config.run.seed)
      .integer("particles", static_cast<std::int64_t>(stack.filter().particle_count()))
      .text("localization", stack::to_string(stack.localization()))
      .text("stop_reason", stack::to_string(stack.stop_reason()));
  optional_number(json, "coverage", score.coverage);
  optional_number(json, "ate_rmse_m", score.ate_rmse_m);
  optional_number(json, "odometry_ate_rmse_m", score.odometry_ate_rmse_m);
  optional_number(json, "map_agreement", score.map_agreement);
  if (context.has_collisions) {
    json.unsigned_integer("collisions", context.collisions)
        .unsigned_integer("collision_events", context.collision_events)
        .unsigned_integer("collision_events_people", context.person_collision_events)
        .unsigned_integer("person_contacts", context.person_contacts);
    number_rows(json, "collision_log", context.collision_log);
    json.number("near_miss_m", context.near_miss_m).unsigned_integer("near_misses", context.near_misses);
    number_rows(json, "near_miss_log", context.near_miss_log);
    write_door_visits(json, context);
  } else {
    json.null("collisions").null("collision_events").null("collision_events_people").null("person_contacts");
    json.null("near_miss_m").null("near_misses");
    json.null("door_visit_reach_m").null("door_visits");
  }
  json.unsigned_integer("updates", stack.counters().updates)
      .unsigned_integer("landmarks", score.landmarks)
      .unsigned_integer("landmark_identities", stack.landmark_count());
  write_identity_check(json, stack.identity_check());
  write_identity_gate(json, stack.identity_gate());
  json.number("grids_held_mean", grid.mean_grids_held())
      .unsigned_integer("grids_held_max", grid.grids_held_max)
      .unsigned_integer("resamplings", stack.filter().counters().resamplings)
      .number("sim_time_s", stack.time_s())
      .number("wall_time_s", context.wall_time_s)
      .number("distance_m", context.distance_m);
  for (const auto& [key, value] : context.extra_numbers) json.number(key.c_str(), value);
  write_coverage_curve(json, context.coverage_curve);
  write_timing(json, stack.scheduler());
  write_pools(json, stack, config);
  write_final_map(json, score.final_map, stack.scan_archive().stats());
  json.unsigned_integer("heap_allocations_in_loop", stack.counters().heap_allocations_in_loop);
  write_counters(json, stack);
  json.begin_object("outputs_sha256");
  for (const auto& [file, digest] : digests) json.text(file.c_str(), digest);
  json.end_object();
  json.end_object();
  return json.str();
}

}  // namespace

MapOverlays map_overlays(const stack::Stack& stack) {
  MapOverlays overlays;
  for (const auto& [index, pose] : ml_trajectory(stack.filter())) overlays.estimated_trajectory.push_back(pose.translation());
  for (const core::Pose2& pose : stack.odometry_path()) overlays.raw_odometry.push_back(pose.translation());
  for (const Eigen::Vector2d& waypoint : stack.explorer().plan().waypoints) overlays.plan.push_back(waypoint);
  return overlays;
}

std::string sha256_of_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return {};
  report::Sha256 hash;
  std::vector<char> buffer(1 << 20);
  while (file) {
    file.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    hash.update(reinterpret_cast<const std::uint8_t*>(buffer.data()), static_cast<std::size_t>(file.gcount()));
  }
  return hash.finish_hex();
}

std::string write_run_directory(const stack::Stack& stack, const core::SystemConfig& config, const RunContext& context,
                                const std::string& out, RunScore& score) {
  std::string error;
  if (!write_trajectories(stack, out, error).empty()) return error;
  std::ostringstream ply;
  score.landmarks = slam::write_landmarks_ply(ply, stack.filter().landmarks(), stack.filter().ml_map(),
                                              static_cast<std::uint32_t>(config.filter.export_min_observations));
  if (!write_text(out + "/landmarks.ply", ply.str(), error)) return error;
  if (!write_text(out + "/explore_events.csv", explore_events_csv(stack.explorer().journal()), error)) return error;
  occupancy::RosMap map;
  error = write_maps(stack, config, out, map, score.final_map);
  if (!error.empty()) return error;
  score_trajectories(stack, score);
  score_map(stack, config, context, score);
  std::map<std::string, std::string> digests;
  std::vector<std::string> files = {"map.pgm",      "map.yaml",      "map.png",
                                    "trajectory.tum", "odometry.tum", "landmarks.ply", "explore_events.csv"};
  if (every_update_has_truth(stack)) files.push_back("groundtruth.tum");
  if (!context.log_file.empty()) files.push_back(context.log_file);
  for (const std::string& file : files) digests[file] = sha256_of_file(out + "/" + file);
  write_text(out + "/report.json", report_json(stack, config, context, score, digests), error);
  return error;
}

}  // namespace stereoscout::cli
