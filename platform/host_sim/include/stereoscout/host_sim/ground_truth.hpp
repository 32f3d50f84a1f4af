#pragma once
// Ground truth of a world for the robot's height band: which geometry blocks a robot of a
// given height, a collision test for its footprint disc, the occupancy grid a perfect mapper
// would produce, and the free space reachable from the start pose (for coverage figures).
// Start-up / evaluation code: these allocate.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::host_sim {

// The obstacles whose z-range intersects [band_low, band_high] (static geometry only; people
// are added at their current position by the caller that knows the time).
class ObstacleBand {
 public:
  ObstacleBand(const World& world, double band_low_m, double band_high_m);

  // True when a disc of `radius` centred at `point` overlaps a blocking obstacle.
  bool disc_collides(const Eigen::Vector2d& point, double radius) const;
  // True when the straight line from `a` to `b` passes through an obstacle (a line of sight).
  bool blocks_line(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
  // The obstacle point nearest to `point` (`point` itself when the band is empty).
  Eigen::Vector2d nearest_point(const Eigen::Vector2d& point) const;

  struct Segment {
    Eigen::Vector2d a;
    Eigen::Vector2d b;
  };
  const std::vector<Segment>& segments() const { return segments_; }

 private:
  std::vector<Segment> segments_;                         // walls and prism edges in the band
  std::vector<const std::vector<Eigen::Vector2d>*> solids_;  // prism footprints in the band
  std::vector<Eigen::Vector3d> discs_;                    // cylinders in the band: (x, y, radius)
};

Eigen::Vector2d nearest_on_segment(const Eigen::Vector2d& point, const Eigen::Vector2d& a, const Eigen::Vector2d& b);
double distance_to_segment(const Eigen::Vector2d& point, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// A grid over the world's bounds: cell (ix, iy) covers [origin + ix * resolution, ...);
// row iy = 0 is the lowest y.
struct GroundTruthGrid {
  enum Cell : std::uint8_t { free = 0, occupied = 1, unknown = 2 };
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // world position of the corner of cell (0, 0)
  double resolution_m = 0.05;
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> cells;  // row-major, width * height

  std::uint8_t at(int ix, int iy) const {
    return cells[static_cast<std::size_t>(iy) * static_cast<std::size_t>(width) + static_cast<std::size_t>(ix)];
  }
  std::uint8_t& at(int ix, int iy) {
    return cells[static_cast<std::size_t>(iy) * static_cast<std::size_t>(width) + static_cast<std::size_t>(ix)];
  }
  bool contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < width && iy < height; }
  Eigen::Vector2d cell_center(int ix, int iy) const {
    return origin + resolution_m * Eigen::Vector2d(ix + 0.5, iy + 0.5);
  }
  // Cell containing `point` (may be outside the grid; check with contains()).
  Eigen::Vector2i cell_of(const Eigen::Vector2d& point) const;
  std::size_t count(std::uint8_t value) const;
};

// Rasterises the static obstacles of the band [band_low_m, band_high_m] (use
// sim.floor_tolerance_m and robot.height_m): a cell is occupied when an obstacle comes within
// half the cell's diagonal of its centre (so a wall is a connected line of cells at any
// resolution). Everything else is free. The grid covers the world's bounds plus `margin_m`.
GroundTruthGrid rasterize_world(const World& world, double resolution_m, double band_low_m, double band_high_m,
                                double margin_m = 0.5);

// Free cells where the centre of a robot of `robot_radius_m` can go, starting from
// `start` and moving without its disc touching an occupied cell (flood fill, 4-connected,
// over the occupancy grid inflated by the radius). Reachable cells are `free`, obstacles
// `occupied`, free but unreachable cells `unknown`. Empty grid of unknowns if the start is blocked.
GroundTruthGrid reachable_free_space(const GroundTruthGrid& occupancy, const Eigen::Vector2d& start,
                                     double robot_radius_m);

// ROS map_server files: `<stem>.pgm` (0 occupied, 254 free, 205 unknown; the top image row is
// the highest y) and, when `yaml_path` is not empty, the yaml with image, resolution,
// origin [x, y, 0], negate 0, occupied_thresh 0.65, free_thresh 0.196. Returns an error text
// or an empty string.
std::string write_map_pgm(const GroundTruthGrid& grid, const std::string& pgm_path);
std::string write_map_yaml(const GroundTruthGrid& grid, const std::string& yaml_path, const std::string& image_name);

}  // namespace stereoscout::host_sim
