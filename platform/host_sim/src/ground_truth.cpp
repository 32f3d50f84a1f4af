#include "stereoscout/host_sim/ground_truth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>

namespace stereoscout::host_sim {
namespace {

bool in_band(double z_min, double z_max, double band_low, double band_high) {
  return z_max > band_low && z_min < band_high;
}

}  // namespace

Eigen::Vector2d nearest_on_segment(const Eigen::Vector2d& point, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d edge = b - a;
  const double length_squared = edge.squaredNorm();
  const double s = length_squared > 0.0 ? std::clamp((point - a).dot(edge) / length_squared, 0.0, 1.0) : 0.0;
  return a + s * edge;
}

double distance_to_segment(const Eigen::Vector2d& point, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (nearest_on_segment(point, a, b) - point).norm();
}

ObstacleBand::ObstacleBand(const World& world, double band_low_m, double band_high_m) {
  for (const WallPiece& wall : world.walls) {
    if (in_band(wall.z_min, wall.z_max, band_low_m, band_high_m)) segments_.push_back({wall.a, wall.b});
  }
  for (const Prism& prism : world.prisms) {
    if (!in_band(prism.z_min, prism.z_max, band_low_m, band_high_m)) continue;
    solids_.push_back(&prism.polygon);
    for (std::size_t i = 0; i < prism.polygon.size(); ++i) {
      segments_.push_back({prism.polygon[i], prism.polygon[(i + 1) % prism.polygon.size()]});
    }
  }
  for (const Cylinder& cylinder : world.cylinders) {
    if (in_band(cylinder.z_min, cylinder.z_max, band_low_m, band_high_m)) {
      discs_.emplace_back(cylinder.center.x(), cylinder.center.y(), cylinder.radius);
    }
  }
}

bool ObstacleBand::disc_collides(const Eigen::Vector2d& point, double radius) const {
  for (const Segment& segment : segments_) {
    if (distance_to_segment(point, segment.a, segment.b) < radius) return true;
  }
  for (const auto* polygon : solids_) {
    if (polygon_contains(*polygon, point)) return true;
  }
  for (const Eigen::Vector3d& disc : discs_) {
    if ((point - disc.head<2>()).norm() < radius + disc.z()) return true;
  }
  return false;
}

bool ObstacleBand::blocks_line(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); };
  const Eigen::Vector2d ray = b - a;
  for (const Segment& segment : segments_) {
    const Eigen::Vector2d edge = segment.b - segment.a;
    const double denominator = cross(ray, edge);
    if (denominator == 0.0) continue;  // parallel: a grazing line of sight is not blocked
    const double along_ray = cross(segment.a - a, edge) / denominator;
    const double along_edge = cross(segment.a - a, ray) / denominator;
    if (along_ray > 0.0 && along_ray < 1.0 && along_edge >= 0.0 && along_edge <= 1.0) return true;
  }
  for (const Eigen::Vector3d& disc : discs_) {
    if (distance_to_segment(disc.head<2>(), a, b) < disc.z()) return true;
  }
  return false;
}

Eigen::Vector2d ObstacleBand::nearest_point(const Eigen::Vector2d& point) const {
  Eigen::Vector2d nearest = point;
  double best = std::numeric_limits<double>::infinity();
  for (const Segment& segment : segments_) {
    const Eigen::Vector2d candidate = nearest_on_segment(point, segment.a, segment.b);
    const double distance = (candidate - point).norm();
    if (distance >= best) continue;
    best = distance;
    nearest = candidate;
  }
  for (const Eigen::Vector3d& disc : discs_) {
    const Eigen::Vector2d offset = point - disc.head<2>();
    const double distance = offset.norm();
    if (distance <= 0.0 || distance - disc.z() >= best) continue;
    best = distance - disc.z();
    nearest = disc.head<2>() + offset * (disc.z() / distance);
  }
  return nearest;
}

Eigen::Vector2i GroundTruthGrid::cell_of(const Eigen::Vector2d& point) const {
  const Eigen::Vector2d cell = (point - origin) / resolution_m;
  return {static_cast<int>(std::floor(cell.x())), static_cast<int>(std::floor(cell.y()))};
}

std::size_t GroundTruthGrid::count(std::uint8_t value) const {
  return static_cast<std::size_t>(std::count(cells.begin(), cells.end(), value));
}

GroundTruthGrid rasterize_world(const World& world, double resolution_m, double band_low_m, double band_high_m,
                                double margin_m) {
  GroundTruthGrid grid;
  grid.resolution_m = resolution_m;
  grid.origin = world.bounds_min() - Eigen::Vector2d::Constant(margin_m);
  const Eigen::Vector2d extent = world.bounds_max() + Eigen::Vector2d::Constant(margin_m) - grid.origin;
  grid.width = std::max(1, static_cast<int>(std::ceil(extent.x() / resolution_m)));
  grid.height = std::max(1, static_cast<int>(std::ceil(extent.y() / resolution_m)));
  grid.cells.assign(static_cast<std::size_t>(grid.width) * static_cast<std::size_t>(grid.height), GroundTruthGrid::free);
  const ObstacleBand band(world, band_low_m, band_high_m);
  // A cell is occupied when an obstacle comes within the cell's half diagonal of its centre
  // (then it overlaps the cell's circumscribed disc; conservative by design, as a mapper
  // marks a cell hit by any return).
  const double half_diagonal = 0.5 * std::sqrt(2.0) * resolution_m;
  for (int iy = 0; iy < grid.height; ++iy) {
    for (int ix = 0; ix < grid.width; ++ix) {
      if (band.disc_collides(grid.cell_center(ix, iy), half_diagonal)) grid.at(ix, iy) = GroundTruthGrid::occupied;
    }
  }
  return grid;
}

GroundTruthGrid reachable_free_space(const GroundTruthGrid& occupancy, const Eigen::Vector2d& start,
                                     double robot_radius_m) {
  GroundTruthGrid result = occupancy;
  // Inflate: a cell is blocked for the robot's centre when an occupied cell centre lies
  // within the radius.
  const int reach = static_cast<int>(std::ceil(robot_radius_m / occupancy.resolution_m));
  std::vector<std::uint8_t> blocked(occupancy.cells.size(), 0);
  for (int iy = 0; iy < occupancy.height; ++iy) {
    for (int ix = 0; ix < occupancy.width; ++ix) {
      if (occupancy.at(ix, iy) != GroundTruthGrid::occupied) continue;
      for (int dy = -reach; dy <= reach; ++dy) {
        for (int dx = -reach; dx <= reach; ++dx) {
          if (!occupancy.contains(ix + dx, iy + dy)) continue;
          if (std::hypot(dx, dy) * occupancy.resolution_m > robot_radius_m) continue;
          blocked[static_cast<std::size_t>(iy + dy) * static_cast<std::size_t>(occupancy.width) + static_cast<std::size_t>(ix + dx)] = 1;
        }
      }
    }
  }
  for (std::uint8_t& cell : result.cells) {
    if (cell == GroundTruthGrid::free) cell = GroundTruthGrid::unknown;
  }
  const Eigen::Vector2i first = occupancy.cell_of(start);
  auto index = [&](int ix, int iy) {
    return static_cast<std::size_t>(iy) * static_cast<std::size_t>(occupancy.width) + static_cast<std::size_t>(ix);
  };
  if (!occupancy.contains(first.x(), first.y()) || blocked[index(first.x(), first.y())] != 0) return result;
  std::deque<Eigen::Vector2i> queue{first};
  result.at(first.x(), first.y()) = GroundTruthGrid::free;
  const int steps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  while (!queue.empty()) {
    const Eigen::Vector2i cell = queue.front();
    queue.pop_front();
    for (const auto& step : steps) {
      const int nx = cell.x() + step[0];
      const int ny = cell.y() + step[1];
      if (!occupancy.contains(nx, ny) || blocked[index(nx, ny)] != 0 || result.at(nx, ny) != GroundTruthGrid::unknown) continue;
      result.at(nx, ny) = GroundTruthGrid::free;
      queue.emplace_back(nx, ny);
    }
  }
  return result;
}

std::string write_map_pgm(const GroundTruthGrid& grid, const std::string& pgm_path) {
  std::FILE* file = std::fopen(pgm_path.c_str(), "wb");
  if (file == nullptr) return "cannot write " + pgm_path;
  std::fprintf(file, "P5\n# stereoscout ground truth, resolution %g m\n%d %d\n255\n", grid.resolution_m, grid.width, grid.height);
  std::vector<unsigned char> row(static_cast<std::size_t>(grid.width));
  for (int iy = grid.height - 1; iy >= 0; --iy) {  // image top = highest y (map_server convention)
    for (int ix = 0; ix < grid.width; ++ix) {
      const std::uint8_t cell = grid.at(ix, iy);
      row[static_cast<std::size_t>(ix)] = cell == GroundTruthGrid::occupied ? 0 : cell == GroundTruthGrid::free ? 254 : 205;
    }
    std::fwrite(row.data(), 1, row.size(), file);
  }
  const bool ok = std::fclose(file) == 0;
  return ok ? std::string() : "error writing " + pgm_path;
}

std::string write_map_yaml(const GroundTruthGrid& grid, const std::string& yaml_path, const std::string& image_name) {
  std::FILE* file = std::fopen(yaml_path.c_str(), "w");
  if (file == nullptr) return "cannot write " + yaml_path;
  std::fprintf(file, "image: %s\nresolution: %.6f\norigin: [%.6f, %.6f, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
               image_name.c_str(), grid.resolution_m, grid.origin.x(), grid.origin.y());
  const bool ok = std::fclose(file) == 0;
  return ok ? std::string() : "error writing " + yaml_path;
}

}  // namespace stereoscout::host_sim
