// Cost of the exploration work done after every observation update on the paper's 70 m grid
// (700 x 700 cells of 0.1 m, or 1400 x 1400 of 0.05 m): navigation map rebuild (distance
// transforms, inflation), reachability and goal selection (H on the candidate lattice), and
// one A* plan across the explored area.
//
// Scene: a building of `size` x `size` metres centred in the grid, split into 4 m rooms with
// 1 m doors, of which the western `explored` fraction is known (free floor, walls occupied)
// and the rest unknown, as in the middle of a run. The cell size is the third argument (cm);
// at 5 cm the margin and the candidate lattice keep their metric size, as in a 5 cm config.
#include <cmath>
#include <cstdint>
#include <vector>

#include <benchmark/benchmark.h>

#include "stereoscout/explore/explorer.hpp"

namespace stereoscout::explore {
namespace {

constexpr double kGridSide_m = 70.0;
constexpr double kRoom_m = 4.0;
constexpr double kDoor_m = 1.0;

int cells_in(double metres, double resolution_m) { return static_cast<int>(std::lround(metres / resolution_m)); }

struct Scene {
  double resolution_m;
  int grid;  // cells on a side
  std::vector<std::uint8_t> cells;
  GridView view;
  Eigen::Vector2d robot;
  Eigen::Vector2i far_cell;

  Scene(double building_m, double explored_percent, double cell_m)
      : resolution_m(cell_m),
        grid(cells_in(kGridSide_m, resolution_m)),
        cells(static_cast<std::size_t>(grid) * static_cast<std::size_t>(grid), 0) {
    const int building = cells_in(building_m, resolution_m);
    const double explored = explored_percent / 100.0;
    const int room = cells_in(kRoom_m, resolution_m);
    const int door0 = cells_in(0.5 * (kRoom_m - kDoor_m), resolution_m);
    const int door1 = door0 + cells_in(kDoor_m, resolution_m);
    const int x0 = (grid - building) / 2;
    const int known_x1 = x0 + static_cast<int>(explored * building);
    auto set = [&](int x, int y, CellState state) {
      cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(grid) + static_cast<std::size_t>(x)] =
          static_cast<std::uint8_t>(state);
    };
    for (int y = x0; y < x0 + building; ++y) {
      for (int x = x0; x < known_x1; ++x) {
        const int rx = (x - x0) % room;
        const int ry = (y - x0) % room;
        const bool wall = (rx == 0 || ry == 0) &&
                          !((rx == 0 && ry >= door0 && ry < door1) || (ry == 0 && rx >= door0 && rx < door1));
        const bool border = x == x0 || y == x0 || y == x0 + building - 1;
        set(x, y, wall || border ? CellState::occupied : CellState::free);
      }
    }
    view.width = grid;
    view.height = grid;
    view.resolution_m = resolution_m;
    view.cells = cells.data();
    const int inset = cells_in(2.0, resolution_m);
    robot = view.center(x0 + inset, x0 + inset);
    far_cell = Eigen::Vector2i(known_x1 - inset, x0 + building - inset);
  }

  // The default config's, with the cell-counted margin and lattice kept at their metric size.
  ExploreParams params() const {
    ExploreParams params =
        ExploreParams::from_config(core::ExploreConfig{}, core::RobotConfig{}, core::CameraConfig{},
                                   core::VisionConfig{}, grid, grid);
    const double scale = 0.1 / resolution_m;
    params.explore.lethal_margin_cells *= scale;
    params.explore.candidate_stride_cells = static_cast<int>(std::lround(params.explore.candidate_stride_cells * scale));
    return params;
  }
};

// Arguments: building size in metres, explored percent, cell size in cm.
Scene scene_of(const benchmark::State& state) {
  return Scene(static_cast<double>(state.range(0)), static_cast<double>(state.range(1)),
               static_cast<double>(state.range(2)) / 100.0);
}

void BM_NavigationMapRebuild(benchmark::State& state) {
  const Scene scene = scene_of(state);
  NavigationMap map(scene.params());
  for (auto _ : state) benchmark::DoNotOptimize(map.rebuild(scene.view, scene.robot, scene.robot));
}

// Goal selection over candidates on a lattice of `stride` cells (1: every cell).
void run_goal_selection(benchmark::State& state, int stride) {
  const Scene scene = scene_of(state);
  ExploreParams params = scene.params();
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
  const Scene scene = scene_of(state);
  const ExploreParams params = scene.params();
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
  const Scene scene(20.0, 50.0, 0.1);
  const int x0 = (scene.grid - 200) / 2;
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

// The paper's lab (about 20 m) half and mostly explored; a 60 m building 80% explored; each at
// 10 cm cells and the lab's at 5 cm too.
#define SCENES                                                                                              \
  Args({20, 50, 10})->Args({20, 90, 10})->Args({60, 80, 10})->Args({20, 50, 5})->Args({20, 90, 5})->Args( \
      {60, 80, 5})->Unit(benchmark::kMillisecond)
BENCHMARK(BM_NavigationMapRebuild)->SCENES;
BENCHMARK(BM_GoalSelection)->SCENES;
BENCHMARK(BM_GoalSelectionFullResolution)->Args({20, 50, 10})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AStarAcrossTheBuilding)->SCENES;
BENCHMARK(BM_DoorHeading)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace stereoscout::explore

BENCHMARK_MAIN();
