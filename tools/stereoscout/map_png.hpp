#pragma once
// map.png: the occupancy map with the estimated trajectory, the raw odometry and the current
// plan drawn over it, as in the paper's figures 4, 6 and 8. Host-only (PNG via OpenCV).
// The paths are plain lists of map-frame points, so any module's trajectory or plan fits.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "stereoscout/occupancy/ros_map.hpp"

namespace stereoscout::cli {

struct MapOverlays {
  std::vector<Eigen::Vector2d> estimated_trajectory;  // drawn blue
  std::vector<Eigen::Vector2d> raw_odometry;          // drawn red
  std::vector<Eigen::Vector2d> plan;                  // drawn green
};

// Empty string on success, else an error naming the file.
std::string write_map_png(const occupancy::RosMap& map, const MapOverlays& overlays, const std::string& png_path);

}  // namespace stereoscout::cli
