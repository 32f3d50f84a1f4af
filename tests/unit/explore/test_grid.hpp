#pragma once
// Hand-made grids for the exploration tests.

#include <cstdint>
#include <vector>

#include "stereoscout/core/config/camera.hpp"
#include "stereoscout/core/config/explore.hpp"
#include "stereoscout/core/config/robot.hpp"
#include "stereoscout/explore/grid_view.hpp"

namespace stereoscout::explore::testing {

struct TestGrid {
  TestGrid(int width, int height, CellState fill_state, double resolution_m = 0.1)
      : width_(width),
        height_(height),
        resolution_m_(resolution_m),
        cells(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), static_cast<std::uint8_t>(fill_state)) {}

  // Cells [x0, x1) x [y0, y1).
  void fill(int x0, int y0, int x1, int y1, CellState state) {
    for (int y = y0; y < y1; ++y) {
      for (int x = x0; x < x1; ++x) set(x, y, state);
    }
  }
  void set(int x, int y, CellState state) {
    cells[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)] =
        static_cast<std::uint8_t>(state);
  }
  // Occupied border around the whole grid.
  void walls() {
    fill(0, 0, width_, 1, CellState::occupied);
    fill(0, height_ - 1, width_, height_, CellState::occupied);
    fill(0, 0, 1, height_, CellState::occupied);
    fill(width_ - 1, 0, width_, height_, CellState::occupied);
  }
  GridView view() const {
    GridView grid;
    grid.width = width_;
    grid.height = height_;
    grid.resolution_m = resolution_m_;
    grid.origin_m = Eigen::Vector2d::Zero();
    grid.cells = cells.data();
    return grid;
  }

  int width_;
  int height_;
  double resolution_m_;
  std::vector<std::uint8_t> cells;
};

inline ExploreParams test_params(int width, int height, bool has_pan_unit = true) {
  core::RobotConfig robot;
  core::CameraConfig camera;
  camera.has_pan_unit = has_pan_unit;
  // The scenes put obstacles into free cells from one step to the next, as a passer-by does;
  // the tests of waiting for walkers switch it on themselves.
  core::ExploreConfig explore;
  explore.wait_for_walkers = false;
  return ExploreParams::from_config(explore, robot, camera, core::VisionConfig{}, width, height);
}

}  // namespace stereoscout::explore::testing
