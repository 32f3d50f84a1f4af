#pragma once
// The run directory of design.md section 4, written at the end of `explore`, `replay` and
// `run`: map.pgm + map.yaml (final map of the ML trajectory), map.png (map, estimated
// trajectory, raw odometry, last plan), trajectory.tum, odometry.tum, groundtruth.tum (when
// the true pose is known), landmarks.ply, explore_events.csv (the explorer's journal), and
// report.json (docs/report.md) with a SHA-256 of every other file, the sensor log included
// when it is in the directory.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "map_png.hpp"
#include "stereoscout/core/system_config.hpp"
#include "stereoscout/host_sim/world.hpp"
#include "stereoscout/occupancy/final_map.hpp"
#include "stereoscout/stack/stack.hpp"

namespace stereoscout::cli {

// What the command knows beyond the stack.
struct RunContext {
  std::string command;                         // explore, replay, run
  std::string world_name;                      // empty on the robot
  const host_sim::World* world = nullptr;      // ground truth for coverage and map agreement
  bool has_collisions = false;                 // the simulator counts them
  std::uint64_t collisions = 0;
  std::uint64_t collision_events = 0;
  std::uint64_t person_collision_events = 0;   // those of them into a person
  // The first contacts: time s, true x, y, theta, and the person run into (their index in the
  // world's people) or -1 for a static obstacle.
  std::vector<std::array<double, 8>> collision_log;  // docs/report.md, `collision_log`
  std::uint64_t person_contacts = 0;
  double near_miss_m = 0.0;                    // the simulator's threshold; near misses below
  std::uint64_t near_misses = 0;
  std::vector<std::array<double, 5>> near_miss_log;  // time s, true x, y, theta, least clearance m
  double door_visit_reach_m = 0.0;             // the simulator's door visit zone beyond the radius
  std::uint64_t door_visits = 0;
  std::uint64_t door_crossings = 0;
  std::uint64_t door_visits_touched = 0;
  // time s, door index, true x, y, least clearance m, crossed (0/1), touched (0/1)
  std::vector<std::array<double, 7>> door_visit_log;  // docs/report.md, `door_visit_log`
  double distance_m = 0.0;                     // driven (simulator), 0 if unknown
  double wall_time_s = 0.0;
  std::string log_file;                        // file name inside the run directory, or empty
  std::vector<std::pair<std::string, double>> extra_numbers;   // e.g. replay damage counts
  std::vector<std::pair<double, double>> coverage_curve;       // (time s, coverage) samples
};

struct RunScore {
  double coverage = -1.0;        // < 0: unknown (no ground truth)
  double map_agreement = -1.0;
  double ate_rmse_m = -1.0;
  double odometry_ate_rmse_m = -1.0;
  std::size_t landmarks = 0;
  occupancy::TrajectoryScanCounts final_map;  // where map.pgm's scans came from
};

// Writes everything into `out` (which must exist). Returns an empty string on success, else
// an error naming the file. `score` receives the figures for the command's summary line.
std::string write_run_directory(const stack::Stack& stack, const core::SystemConfig& config, const RunContext& context,
                                const std::string& out, RunScore& score);

// What map.png draws over a map, as the stack has it now: the ML trajectory, the raw
// odometry and the current plan (also the navigation snapshots' pictures).
MapOverlays map_overlays(const stack::Stack& stack);

// SHA-256 of a file's bytes as lower-case hex ("" when it cannot be read).
std::string sha256_of_file(const std::string& path);

}  // namespace stereoscout::cli
