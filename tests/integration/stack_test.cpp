// The whole stack through the `stereoscout` command (issue 8), short versions: a small
// world, a 320 x 240 camera and few particles, so that each run takes seconds. The full lab
// runs are `stereoscout explore` (docs/results.md).
//  - two runs with the same seed give the same output files (SHA-256 in report.json);
//  - `replay` of the recorded log gives the same output files as the live run;
//  - a log with flipped bytes and a truncated log replay to the end, damage counted;
//  - the tick loop does not touch the heap (outside OpenCV's SIFT, counted apart);
//  - report.json has every key docs/report.md promises.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "stereoscout/test/command.hpp"
#include "stereoscout/test/small_world.hpp"

namespace stereoscout {
namespace {

namespace fs = std::filesystem;

constexpr const char* kWorld = test::kTwoRoomsWorld;

// A small camera and map so that a run of a few simulated seconds takes seconds.
std::string config_text(const std::string& world_path, int scan_history = 512, double lineage_margin = 0.0,
                        bool identity_gate = false, const std::string& filter_extra = "") {
  return "%YAML:1.0\n"
         "run: {seed: 7, max_time_s: 12, world: \"" + world_path + "\"}\n"
         "camera: {width_px: 320, height_px: 240, focal_px: 200, principal_x_px: 159.5, principal_y_px: 119.5}\n"
         "vision: {max_features: 300, dense_num_disparities: 32, max_disparity_px: 64, identity_gate: " +
         std::string(identity_gate ? "true" : "false") + "}\n"
         "filter: {particles: 20, particle_capacity: 20, landmark_node_capacity: 200000, "
         "landmark_estimate_capacity: 100000, trajectory_node_capacity: 20000, estimate_lineage_margin: " +
         std::to_string(lineage_margin) + filter_extra + "}\n"
         "grid: {width_cells: 160, height_cells: 160, final_map_resolution_m: 0.05, scan_history: " +
         std::to_string(scan_history) + "}\n";
}

class StackRun : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    dir_ = fs::temp_directory_path() / ("stereoscout_stack_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    std::ofstream(dir_ / "world.yaml") << kWorld;
    std::ofstream(dir_ / "config.yaml") << config_text((dir_ / "world.yaml").string());
  }
  void TearDown() override { fs::remove_all(dir_); }

  test::CommandResult explore(const std::string& out) {
    return test::run_stereoscout("explore --config " + (dir_ / "config.yaml").string() + " --out " + (dir_ / out).string());
  }
  test::CommandResult replay(const fs::path& log, const std::string& out) {
    return test::run_stereoscout("replay " + log.string() + " --out " + (dir_ / out).string());
  }
  std::string report(const std::string& out) const {
    std::ifstream file(dir_ / out / "report.json");
    std::stringstream text;
    text << file.rdbuf();
    return text.str();
  }
  // Replays the run in `live` and checks that it gives the live run's output files (all but
  // the log it reads).
  void expect_replay_gives_the_outputs_of(const std::string& live);

  fs::path dir_;
};

// The "outputs_sha256" object of a report: file name -> digest.
std::map<std::string, std::string> output_digests(const std::string& report) {
  std::map<std::string, std::string> digests;
  const std::size_t start = report.find("\"outputs_sha256\": {");
  if (start == std::string::npos) return digests;
  std::istringstream lines(report.substr(start, report.find('}', start) - start));
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line)) {
    const std::size_t a = line.find('"');
    const std::size_t b = line.find('"', a + 1);
    const std::size_t c = line.find('"', b + 1);
    const std::size_t d = line.find('"', c + 1);
    if (d == std::string::npos) continue;
    digests[line.substr(a + 1, b - a - 1)] = line.substr(c + 1, d - c - 1);
  }
  return digests;
}

// The number after "key": in a report (or -1 when missing / null).
double report_number(const std::string& report, const std::string& key) {
  const std::size_t at = report.find("\"" + key + "\": ");
  if (at == std::string::npos) return -1.0;
  const std::string rest = report.substr(at + key.size() + 4, 32);
  if (rest.compare(0, 4, "null") == 0) return -1.0;
  return std::stod(rest);
}

void StackRun::expect_replay_gives_the_outputs_of(const std::string& live) {
  const test::CommandResult replayed = replay(dir_ / live / "sensors.log", "replay");
  ASSERT_EQ(replayed.exit_code, 0) << replayed.output;
  std::map<std::string, std::string> expected = output_digests(report(live));
  expected.erase("sensors.log");
  EXPECT_EQ(output_digests(report("replay")), expected);
}

TEST_F(StackRun, SameSeedSameOutputsNoHeapInLoopAndEveryReportKey) {
  const test::CommandResult first = explore("a");
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const test::CommandResult second = explore("b");
  ASSERT_EQ(second.exit_code, 0) << second.output;
  const std::string a = report("a");
  const std::map<std::string, std::string> digests = output_digests(a);
  for (const char* file : {"map.pgm", "map.yaml", "map.png", "trajectory.tum", "odometry.tum", "groundtruth.tum",
                           "landmarks.ply", "explore_events.csv", "sensors.log"}) {
    ASSERT_EQ(digests.count(file), 1U) << file << " missing from outputs_sha256\n" << a;
    EXPECT_EQ(digests.at(file).size(), 64U) << file;
  }
  EXPECT_EQ(digests, output_digests(report("b")));
  EXPECT_GT(report_number(a, "updates"), 10.0) << a;
  EXPECT_GT(report_number(a, "landmarks"), 0.0) << a;
  EXPECT_EQ(report_number(a, "heap_allocations_in_loop"), 0.0) << a;
  for (const char* key : {"coverage", "ate_rmse_m", "odometry_ate_rmse_m", "map_agreement", "collisions",
                          "collision_events_people", "updates", "landmarks", "grids_held_mean", "grids_held_max",
                          "resamplings", "sim_time_s", "wall_time_s", "reobservation_consistency", "near_miss_m",
                          "near_misses", "door_visit_reach_m", "door_visits", "door_crossings", "door_visits_touched"}) {
    EXPECT_GE(report_number(a, key), 0.0) << key << " missing or null\n" << a;
  }
  // The budget check: generous budgets pass, 1 us budgets fail (no timing is asserted).
  auto profile = [&](const char* name, long long budget_us) {
    std::ofstream file(dir_ / name);
    file << "%YAML:1.0\nbudgets:\n";
    for (const char* task : {"safety", "capture", "odometry", "observation_update", "grid_rollup", "replan", "drive",
                             "logging"}) {
      file << "  " << task << ": {budget_us: " << budget_us << "}\n";
    }
    return (dir_ / name).string();
  };
  const std::string report_path = (dir_ / "a" / "report.json").string();
  EXPECT_EQ(test::run_stereoscout("check-budgets " + report_path + " --profile " + profile("loose.yaml", 100000000)).exit_code, 0);
  const test::CommandResult tight = test::run_stereoscout("check-budgets " + report_path + " --profile " + profile("tight.yaml", 1));
  EXPECT_EQ(tight.exit_code, 1) << tight.output;
  EXPECT_NE(tight.output.find("OVER BUDGET"), std::string::npos) << tight.output;
  for (const char* key : {"\"timing\": {", "\"observation_update\": {", "\"median_us\"", "\"p99_us\"", "\"max_us\"",
                          "\"overruns\"", "\"pools\": {", "\"landmark_nodes\": {", "\"capacity\"", "\"high_water\"",
                          "\"exhausted\""}) {
    EXPECT_NE(a.find(key), std::string::npos) << key << "\n" << a;
  }
}

// --snapshot-at writes what the robot believed at those times, between ticks, and the run is
// the same run: the same output files, no heap allocation counted in the loop.
TEST_F(StackRun, SnapshotsOfTheNavigationGridLeaveTheRunAsItWas) {
  ASSERT_EQ(explore("plain").exit_code, 0);
  const test::CommandResult snapped = test::run_stereoscout("explore --config " + (dir_ / "config.yaml").string() +
                                                            " --snapshot-at 8,4.5 --out " + (dir_ / "snapped").string());
  ASSERT_EQ(snapped.exit_code, 0) << snapped.output;
  EXPECT_EQ(output_digests(report("plain")), output_digests(report("snapped")));
  EXPECT_EQ(report_number(report("snapped"), "heap_allocations_in_loop"), 0.0);
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir_ / "snapped" / "snapshots")) {
    files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  ASSERT_EQ(files.size(), 9U);  // two times, each .pgm, .yaml, .png and -plan.csv, and navigation.csv
  EXPECT_EQ(files.back(), "navigation.csv");
  EXPECT_EQ(files.front().rfind("navigation-4.5", 0), 0U) << files.front();
  std::ifstream summary(dir_ / "snapped" / "snapshots" / "navigation.csv");
  std::string line;
  int lines = 0;
  while (std::getline(summary, line)) ++lines;
  EXPECT_EQ(lines, 3);  // the header and one line a snapshot
  std::ifstream plan(dir_ / "snapped" / "snapshots" / "navigation-8.0-plan.csv");
  ASSERT_TRUE(std::getline(plan, line));
  EXPECT_EQ(line, "x_m,y_m,narrow");

  const test::CommandResult bad = test::run_stereoscout("explore --config " + (dir_ / "config.yaml").string() +
                                                        " --snapshot-at 4,soon --out " + (dir_ / "bad").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("'soon' is not a time"), std::string::npos) << bad.output;
}

// A ring of 4 scans: all but the last 4 of the run's scans reach map.pgm through the archive,
// and a replay still writes the same files.
TEST_F(StackRun, ARunLongerThanTheScanRingKeepsItsWholeFinalMap) {
  std::ofstream(dir_ / "short-ring.yaml") << config_text((dir_ / "world.yaml").string(), 4);
  const test::CommandResult live =
      test::run_stereoscout("explore --config " + (dir_ / "short-ring.yaml").string() + " --out " + (dir_ / "live").string());
  ASSERT_EQ(live.exit_code, 0) << live.output;
  const std::string a = report("live");
  const double updates = report_number(a, "updates");
  EXPECT_GT(updates, 10.0) << a;
  EXPECT_EQ(report_number(a, "scans_archived"), updates - 4.0) << a;
  EXPECT_EQ(report_number(a, "scans_from_ring"), 4.0) << a;
  EXPECT_EQ(report_number(a, "scans_missing"), 0.0) << a;
  EXPECT_NE(a.find("\"archive_on_final_lineage\": true"), std::string::npos) << a;
  expect_replay_gives_the_outputs_of("live");
}

// With filter.estimate_lineage_margin the grid and the explorer follow one particle lineage
// until it dies out, instead of the ML particle of each update: fewer changes of lineage, and
// the run is as reproducible, replayable and free of heap allocation as with the ML particle.
TEST_F(StackRun, WithALineageMarginTheGridChangesLineageLessOftenAndReplaysTheSame) {
  ASSERT_EQ(explore("ml").exit_code, 0);
  std::ofstream(dir_ / "lineage.yaml") << config_text((dir_ / "world.yaml").string(), 512, 10.0);
  const test::CommandResult live =
      test::run_stereoscout("explore --config " + (dir_ / "lineage.yaml").string() + " --out " + (dir_ / "live").string());
  ASSERT_EQ(live.exit_code, 0) << live.output;
  const std::string ml = report("ml");
  const std::string kept = report("live");
  const double ml_switches = report_number(ml, "estimate_lineage_switches");
  const double kept_switches = report_number(kept, "estimate_lineage_switches");
  EXPECT_GT(ml_switches, 0.0) << ml;
  EXPECT_GE(kept_switches, 0.0) << kept;
  EXPECT_LT(kept_switches, ml_switches);
  EXPECT_EQ(report_number(kept, "heap_allocations_in_loop"), 0.0) << kept;
  expect_replay_gives_the_outputs_of("live");
}

// vision.identity_gate: the index's identities split by place. The keys the simulator's truth
// puts elsewhere than their landmark are fewer, and the run is as reproducible, replayable
// and free of heap allocation as without it.
TEST_F(StackRun, WithTheIdentityGateFewerReobservationsLandElsewhereAndTheRunReplaysTheSame) {
  ASSERT_EQ(explore("plain").exit_code, 0);
  std::ofstream(dir_ / "gated.yaml") << config_text((dir_ / "world.yaml").string(), 512, 0.0, true);
  const test::CommandResult live =
      test::run_stereoscout("explore --config " + (dir_ / "gated.yaml").string() + " --out " + (dir_ / "live").string());
  ASSERT_EQ(live.exit_code, 0) << live.output;
  const std::string plain = report("plain");
  const std::string gated = report("live");
  EXPECT_EQ(report_number(plain, "identity_gate"), -1.0) << plain;  // null when off
  EXPECT_GT(report_number(gated, "split"), 0.0) << gated;
  EXPECT_EQ(report_number(gated, "dropped_pool_full"), 0.0) << gated;
  EXPECT_GT(report_number(gated, "reobservation_consistency"), report_number(plain, "reobservation_consistency"))
      << plain << gated;
  EXPECT_EQ(report_number(gated, "heap_allocations_in_loop"), 0.0) << gated;
  expect_replay_gives_the_outputs_of("live");
}

// filter.manhattan_heading_sigma_deg: the scan's walls learn the two rooms' axes (those of
// the world frame, which the filter starts in; the robot starts turned 20 degrees from them)
// and then weigh the particles; the run stays reproducible, replayable and free of heap
// allocation.
TEST_F(StackRun, WithTheBuildingsAxesTheWallsLearnThemAndTheRunReplaysTheSame) {
  std::ofstream(dir_ / "axes.yaml") << config_text((dir_ / "world.yaml").string(), 512, 0.0, false,
                                                   ", manhattan_heading_sigma_deg: 2");
  const test::CommandResult live =
      test::run_stereoscout("explore --config " + (dir_ / "axes.yaml").string() + " --out " + (dir_ / "live").string());
  ASSERT_EQ(live.exit_code, 0) << live.output;
  const std::string axes = report("live");
  EXPECT_EQ(report_number(axes, "manhattan_walls_learnt"), 5.0) << axes;
  EXPECT_GT(report_number(axes, "manhattan_walls_used"), 0.0) << axes;
  EXPECT_NEAR(report_number(axes, "manhattan_axis_deg"), 0.0, 1.0) << axes;
  EXPECT_EQ(report_number(axes, "heap_allocations_in_loop"), 0.0) << axes;
  expect_replay_gives_the_outputs_of("live");
}

// vision.scan_parallel and filter.background_release (the defaults): the dense scan runs on a
// thread of its own beside the filter update, and the maps resampling dropped are released on
// another between updates. The outputs are those of the run with both off (all but the log,
// which records the config), and the loop still does not touch the heap.
TEST_F(StackRun, TheScanAndTheReleaseOnThreadsOfTheirOwnGiveTheOutputsOfTheSequentialRun) {
  // Resampling at almost every update once the robot drives (after its first look), so that
  // there are dropped maps to release.
  const std::string often = "filter: {resample_ess_fraction: 0.99, ";
  std::string parallel = config_text((dir_ / "world.yaml").string());
  auto replace = [](std::string& text, const std::string& from, const std::string& to) {
    ASSERT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
  };
  replace(parallel, "filter: {", often);
  replace(parallel, "max_time_s: 12", "max_time_s: 20");
  std::string sequential = parallel;
  replace(sequential, "identity_gate: false}", "identity_gate: false, scan_parallel: false}");
  replace(sequential, often, often + "background_release: false, ");
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"parallel", parallel}, {"sequential", sequential}}) {
    std::ofstream(dir_ / (name + ".yaml")) << text;
    const test::CommandResult run = test::run_stereoscout("explore --config " + (dir_ / (name + ".yaml")).string() +
                                                          " --out " + (dir_ / name).string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  const std::string parallel_report = report("parallel");
  std::map<std::string, std::string> parallel_outputs = output_digests(parallel_report);
  std::map<std::string, std::string> sequential_outputs = output_digests(report("sequential"));
  ASSERT_EQ(parallel_outputs.erase("sensors.log"), 1U);
  ASSERT_EQ(sequential_outputs.erase("sensors.log"), 1U);
  EXPECT_GE(parallel_outputs.size(), 8U);
  EXPECT_EQ(parallel_outputs, sequential_outputs);
  EXPECT_GT(report_number(parallel_report, "updates"), 10.0);
  EXPECT_GT(report_number(parallel_report, "resamplings"), 5.0);
  EXPECT_EQ(report_number(parallel_report, "heap_allocations_in_loop"), 0.0);
  EXPECT_EQ(report_number(report("sequential"), "heap_allocations_in_loop"), 0.0);
}

TEST_F(StackRun, ReplayGivesTheLiveOutputsAndSurvivesDamage) {
  const test::CommandResult live = explore("live");
  ASSERT_EQ(live.exit_code, 0) << live.output;
  const fs::path log = dir_ / "live" / "sensors.log";
  const test::CommandResult replayed = replay(log, "replay");
  ASSERT_EQ(replayed.exit_code, 0) << replayed.output;
  std::map<std::string, std::string> expected = output_digests(report("live"));
  expected.erase("sensors.log");
  EXPECT_EQ(output_digests(report("replay")), expected);
  EXPECT_EQ(report_number(report("replay"), "log_damaged_places"), 0.0);

  // Flip bytes in the middle of the log (inside some record), and cut it at two thirds.
  const auto size = static_cast<std::streamoff>(fs::file_size(log));
  fs::copy_file(log, dir_ / "flipped.log");
  {
    std::fstream file(dir_ / "flipped.log", std::ios::in | std::ios::out | std::ios::binary);
    for (std::streamoff at : {size / 3, size / 2}) {
      file.seekp(at);
      file.write("\xff\x00\xff\x00\xff\x00\xff\x00", 8);
    }
  }
  fs::copy_file(log, dir_ / "cut.log");
  fs::resize_file(dir_ / "cut.log", static_cast<std::uintmax_t>(size * 2 / 3));

  const test::CommandResult flipped = replay(dir_ / "flipped.log", "flipped");
  ASSERT_EQ(flipped.exit_code, 0) << flipped.output;
  EXPECT_GE(report_number(report("flipped"), "log_damaged_places"), 1.0) << report("flipped");
  EXPECT_GT(report_number(report("flipped"), "updates"), 0.0);

  const test::CommandResult cut = replay(dir_ / "cut.log", "cut");
  ASSERT_EQ(cut.exit_code, 0) << cut.output;
  EXPECT_GT(report_number(report("cut"), "log_truncated_bytes"), 0.0) << report("cut");
  EXPECT_EQ(report_number(report("cut"), "log_end_of_run_seen"), 0.0);
  EXPECT_LT(report_number(report("cut"), "sim_time_s"), report_number(report("live"), "sim_time_s"));
}

}  // namespace
}  // namespace stereoscout
