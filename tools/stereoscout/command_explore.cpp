// stereoscout explore: the whole stack in the simulator until exploration ends.

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "arguments.hpp"
#include "boards.hpp"
#include "commands.hpp"
#include "navigation_snapshot.hpp"
#include "run_directory.hpp"
#include "run_loop.hpp"
#include "reachable_coverage.hpp"
#include "run_setup.hpp"
#include "stereoscout/report/wall_stopwatch.hpp"

namespace stereoscout::cli {
namespace {

constexpr const char* kName = "stereoscout explore";

void declare(Arguments& arguments) {
  arguments.option("config", "FILE", "config file", default_config_path());
  arguments.option("world", "FILE", "world file (default: run.world of the config)");
  arguments.option("seed", "S", "seed of every random stream (default: run.seed)");
  arguments.option("particles", "N", "particles of the filter (default: filter.particles)");
  arguments.option("max-time", "SEC", "stop after this much simulated time (default: run.max_time_s)");
  arguments.option("localization", "SOURCE", "pose source: rbpf, groundtruth or odometry (default: run.localization)");
  arguments.option("out", "DIR", "run directory (created)", "runs/explore");
  arguments.flag("no-log", "do not record the sensor log (no replay possible; saves about 0.6 MB per update)");
  arguments.option("snapshot-at", "T[,T...]",
                   "also write the navigation grid, trajectory and plan as they are at these simulated times "
                   "(into DIR/snapshots/)");
}

}  // namespace

int run_explore(int argc, char** argv) {
  Arguments arguments("explore",
                      "Runs the whole stack in the simulator until exploration ends: simulated stereo camera,\n"
                      "odometry and drive; the tick scheduler on a virtual clock; vision, RBPF, just-in-time grid\n"
                      "and explorer. Writes the run directory (maps, trajectories, landmarks, sensor log,\n"
                      "report.json; see docs/report.md). Same seed, same outputs, byte for byte.");
  declare(arguments);
  if (!arguments.parse(argc, argv)) return arguments.exit_code();
  const auto wall_start = std::chrono::steady_clock::now();
  std::vector<double> snapshot_times;
  std::string error;
  if (arguments.has("snapshot-at") && !parse_snapshot_times(arguments.get("snapshot-at"), snapshot_times, error)) {
    std::fprintf(stderr, "%s: --snapshot-at: %s\n", kName, error.c_str());
    return 2;
  }
  RunSetup setup;
  if (!load_run_setup(arguments, kName, setup)) return 2;
  if (!load_world_of(setup.config, kName, setup)) return 1;
  const std::string out = arguments.get("out");
  std::error_code ignored;
  std::filesystem::create_directories(out, ignored);
  std::filesystem::remove_all(out + "/snapshots", ignored);  // an earlier run's, into the same directory
  log::LogWriter writer(log_writer_options(setup.config, true));
  const bool record = !arguments.has("no-log");
  if (record && !writer.open(out + "/sensors.log", error)) {
    std::fprintf(stderr, "%s: %s\n", kName, error.c_str());
    return 1;
  }
  SimBoard board(setup.config, setup.world);
  report::WallStopwatch stopwatch;
  stack::Stack stack(setup.config, setup.options, board.board(record ? &writer : nullptr), stopwatch);
  if (!stack.start(kStartTimeoutS, error)) {
    std::fprintf(stderr, "%s: %s\n", kName, error.c_str());
    return 1;
  }
  const ReachableCoverage probe(setup.config, setup.world);
  RunContext context;
  LoopHooks hooks;
  hooks.coverage = [&] { return probe.coverage(stack.grid_view()); };
  hooks.sample = [&](double time_s) { context.coverage_curve.emplace_back(time_s, probe.coverage(stack.grid_view())); };
  std::size_t next_snapshot = 0;
  hooks.after_tick = [&](double time_s) {
    for (; next_snapshot < snapshot_times.size() && time_s >= snapshot_times[next_snapshot]; ++next_snapshot) {
      const std::string failed = write_navigation_snapshot(stack, out, snapshot_times[next_snapshot]);
      if (!failed.empty()) std::fprintf(stderr, "%s: snapshot: %s\n", kName, failed.c_str());
    }
  };
  run_to_end(stack, hooks);
  stack.finish();

  context.command = "explore";
  context.world_name = setup.world.name;
  context.world = &setup.world;
  context.has_collisions = true;
  context.collisions = board.simulator().collision_count();
  context.collision_events = board.simulator().collision_event_count();
  context.person_collision_events = board.simulator().person_collision_event_count();
  for (std::size_t i = 0; i < board.simulator().collision_log_size(); ++i) {
    const host_sim::Simulator::CollisionEvent& event = board.simulator().collision_log(i);
    context.collision_log.push_back({event.time_s, event.pose.x, event.pose.y, event.pose.theta,
                                     static_cast<double>(event.person), event.bearing_rad, event.last_in_view_s,
                                     event.in_view_distance_m});
  }
  context.person_contacts = board.simulator().person_contact_count();
  const host_sim::NearMisses& near_misses = board.simulator().near_misses();
  context.near_miss_m = near_misses.threshold_m();
  context.near_misses = near_misses.count();
  for (std::size_t i = 0; i < near_misses.log_size(); ++i) {
    const host_sim::NearMisses::Event& event = near_misses.log(i);
    context.near_miss_log.push_back({event.time_s, event.pose.x, event.pose.y, event.pose.theta, event.clearance_m});
  }
  const host_sim::DoorVisits& door_visits = board.simulator().door_visits();
  context.door_visit_reach_m = setup.config.sim.door_visit_reach_m;
  context.door_visits = door_visits.count();
  context.door_crossings = door_visits.crossings();
  context.door_visits_touched = door_visits.touched_count();
  for (std::size_t i = 0; i < door_visits.log_size(); ++i) {
    const host_sim::DoorVisits::Visit& visit = door_visits.log(i);
    context.door_visit_log.push_back({visit.time_s, static_cast<double>(visit.door), visit.pose.x, visit.pose.y,
                                      visit.clearance_m, visit.crossed ? 1.0 : 0.0, visit.touched ? 1.0 : 0.0});
  }
  context.distance_m = board.simulator().distance_travelled_m();
  context.log_file = record ? "sensors.log" : "";
  context.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return finish_run(stack, setup.config, context, out, kName);
}

}  // namespace stereoscout::cli
