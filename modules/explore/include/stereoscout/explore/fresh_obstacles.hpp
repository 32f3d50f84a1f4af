#pragma once
// Obstacles that just appeared where the grid held free floor: usually a person walking. The
// grid changes only at observation updates (after 7 cm of motion, at most 2 Hz in the stack),
// and a person walking at 0.5 m/s moves 0.3 m in between, so the safety check keeps
// explore.fresh_obstacle_margin_m more clearance from such cells for fresh_obstacle_hold_s
// after they turned occupied. Cells that turn occupied from unknown (a first sighting) are not
// fresh: a static obstacle seen for the first time keeps the ordinary clearance. Off by
// default (margin 0): at 0.3 m it did not reduce the robot's contacts with walking people in
// the three worlds, and it added safety stops (docs/results.md).
//
// observe() compares the grid with the one it saw last; it runs after every observation
// update. Both buffers are sized for the largest grid at construction; nothing is allocated
// after that.

#include <cstdint>
#include <vector>

#include "stereoscout/explore/grid_view.hpp"

namespace stereoscout::explore {

class FreshObstacles {
 public:
  FreshObstacles(const core::ExploreConfig& config, int max_width, int max_height);

  void observe(const GridView& grid, double time_s);
  // True when cell (x, y) of the grid last observed turned from free to occupied within
  // fresh_obstacle_hold_s before time_s.
  bool fresh(const GridView& grid, int x, int y, double time_s) const;
  double margin_m() const { return margin_m_; }

 private:
  double margin_m_;
  double hold_s_;
  int width_ = 0;
  int height_ = 0;
  std::vector<std::uint8_t> previous_;  // CellState of the last grid observed
  std::vector<float> turned_occupied_s_;  // when the cell last turned from free to occupied
};

}  // namespace stereoscout::explore
