// Cost of the exploration work done after every observation update on the paper's 700 x 700
// grid of 0.1 m: navigation map rebuild (distance transforms, inflation), reachability and
// goal selection (H on the candidate lattice), and one A* plan across the explored area.
//
// Scene: a building of `size` x `size` metres centred in the grid, split into 4 m rooms with
// 1 m doors, of which the western `explored` fraction is known (free floor, walls occupied)
// and the rest unknown, as in the middle of a run.
#include <cmath>
#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "stereoscout/explore/explorer.hpp"

namespace stereoscout::explore {
namespace {

constexpr int kGrid = 700;

struct Scene {
  std::vector<std::uint8_t> cells;
  GridView view;
  Eigen::Vector2d robot;
  Eigen::Vector2i far_cell;

  Scene(int building_cells, double explored) : cells(static_cast<std::size_t>(kGrid) * kGrid, 0) {
    const int x0 = (kGrid - building_cells) / 2;
    const int known_x1 = x0 + static_cast<int>(explored * building_cells);
    auto set = [&](int x, int y, CellState state) {
      cells[static_cast<std::size_t>(y) * kGrid + static_cast<std::size_t>(x)] = static_cast<std::uint8_t>(state);
    };
    for (int y = x0; y < x0 + building_cells; ++y) {
      for (int x = x0; x < known_x1; ++x) {
        const int rx = (x - x0) % 40;
        const int ry = (y - x0) % 40;
        const bool wall = (rx == 0 || ry == 0) && !((rx == 0 && ry >= 15 && ry < 25) || (ry == 0 && rx >= 15 && rx < 25));
        const bool border = x == x0 || y == x0 || y == x0 + building_cells - 1;
        set(x, y, wall || border ? CellState::occupied : CellState::free);
      }
    }
    view.width = kGrid;
    view.height = kGrid;
    view.resolution_m = 0.1;
    view.cells = cells.data();
    robot = view.center(x0 + 20, x0 + 20);
    far_cell = Eigen::Vector2i(known_x1 - 20, x0 + building_cells - 20);
  }
};

ExploreParams bench_params() {
  return ExploreParams::from_config(core::ExploreConfig{}, core::RobotConfig{}, core::CameraConfig{}, kGrid, kGrid);
}

// Arguments: building size in cells, explored percent.
void BM_NavigationMapRebuild(benchmark::State& state) {
  const Scene scene(static_cast<int>(state.range(0)), static_cast<double>(state.range(1)) / 100.0);
  NavigationMap map(bench_params());
  for (auto _ : state) benchmark::DoNotOptimize(map.rebuild(scene.view, scene.robot, scene.robot));
}

// Goal selection over candidates on a lattice of `stride` cells (1: every cell).
void run_goal_selection(benchmark::State& state, int stride) {
  const Scene scene(static_cast<int>(state.range(0)), static_cast<double>(state.range(1)) / 100.0);
  ExploreParams params = bench_params();
  if (stride > 0) {
    params.explore.candidate_stride_cells = stride;
  }
  NavigationMap map(params);
  map.rebuild(scene.view, scene.robot, scene.robot);
  GoalMemory memory(512, 0.5, 2.0, 3);
  const GoalValue goal_value(params);
  for (auto _ : state) {
    map.compute_reachable(scene.view.cell_of(scene.robot));
    benchmark::DoNotOptimize(goal_value.select(map, memory, 0.0));
  }
}

void BM_GoalSelection(benchmark::State& state) { run_goal_selection(state, 0); }  // the configured lattice

// Every cell a candidate: the baseline the lattice avoids.
void BM_GoalSelectionFullResolution(benchmark::State& state) { run_goal_selection(state, 1); }

void BM_AStarAcrossTheBuilding(benchmark::State& state) {
  const Scene scene(static_cast<int>(state.range(0)), static_cast<double>(state.range(1)) / 100.0);
  const ExploreParams params = bench_params();
  NavigationMap map(params);
  map.rebuild(scene.view, scene.robot, scene.robot);
  PathPlanner planner(params);
  Plan plan(static_cast<std::size_t>(params.explore.max_plan_waypoints));
  for (auto _ : state) {
    benchmark::DoNotOptimize(planner.plan(map, scene.view.cell_of(scene.robot), scene.far_cell, plan));
  }
  state.counters["path_cells"] = static_cast<double>(plan.cells.size());
}

// The door sighting's heading (explore.door_sighting_heading), done for each scan before a door:
// a 640-column scan from 1.5 m before a 0.9 m door in a measured wall, the estimate turned
// 8 degrees, against the scene's wall in the grid (its line fitted, the turn searched).
void BM_DoorHeading(benchmark::State& state) {
  const Scene scene(200, 50);
  const int x0 = (kGrid - 200) / 2;
  DoorPassage door;
  door.known = true;
  door.middle = scene.view.center(x0, x0 + 20);  // a western door of the first room
  door.along = Eigen::Vector2d(-1.0, 0.0);        // passed westwards, out of the building
  door.width_m = 1.0;
  const core::Pose2 truth{door.middle.x() + 1.5, door.middle.y(), core::kPi};
  core::DepthScan scan;
  scan.columns.resize(640);
  for (std::size_t u = 0; u < scan.columns.size(); ++u) {
    const double bearing = std::atan((320.0 - static_cast<double>(u)) / 400.0);
    const Eigen::Vector2d ray(std::cos(bearing), std::sin(bearing));  // the robot's frame
    const double range = 1.5 / ray.x();
    if (std::abs(range * ray.y()) < 0.5) continue;  // through the door: not measured here
    scan.columns[u].kind = core::DepthScanColumn::Kind::obstacle;
    scan.columns[u].x_robot_m = static_cast<float>(range * ray.x());
    scan.columns[u].y_robot_m = static_cast<float>(range * ray.y());
  }
  const core::Pose2 believed{truth.x, truth.y, core::wrap_angle(truth.theta + core::degrees_to_radians(8.0))};
  double correction_rad = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(DoorSighting::heading_error(scan, believed, door, scene.view, correction_rad));
  }
  state.counters["correction_deg"] = core::radians_to_degrees(correction_rad);
}

// The paper's lab (about 20 m = 200 cells) half and mostly explored; a 60 m building 80% explored.
#define SCENES Args({200, 50})->Args({200, 90})->Args({600, 80})->Unit(benchmark::kMillisecond)
BENCHMARK(BM_NavigationMapRebuild)->SCENES;
BENCHMARK(BM_GoalSelection)->SCENES;
BENCHMARK(BM_GoalSelectionFullResolution)->Args({200, 50})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AStarAcrossTheBuilding)->SCENES;
BENCHMARK(BM_DoorHeading)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace stereoscout::explore

BENCHMARK_MAIN();
