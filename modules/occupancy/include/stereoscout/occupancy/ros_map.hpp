#pragma once
// Occupancy maps in the ROS map_server format: an 8-bit PGM (0 occupied, 254 free, 205
// unknown, top row = highest y) and a YAML file with image, resolution, origin [x, y, yaw],
// negate, occupied_thresh and free_thresh. Written and read with plain stdio (host side, end
// of a run; allocates).

#include <cstdint>
#include <string>
#include <vector>

#include "stereoscout/occupancy/occupancy_grid.hpp"

namespace stereoscout::occupancy {

inline constexpr std::uint8_t kPgmOccupied = 0;
inline constexpr std::uint8_t kPgmFree = 254;
inline constexpr std::uint8_t kPgmUnknown = 205;

// A map as read from (or about to be written to) disk. cells: row-major, row 0 = lowest y.
struct RosMap {
  GridGeometry geometry;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  bool negate = false;
  std::vector<CellState> cells;

  CellState at(int cell_x, int cell_y) const {
    return cells[static_cast<std::size_t>(cell_y) * static_cast<std::size_t>(geometry.width_cells) +
                 static_cast<std::size_t>(cell_x)];
  }
};

RosMap classify_grid(const OccupancyGrid& grid, const CellThresholds& thresholds);

// Writes <pgm_path> and <yaml_path> (the YAML names the PGM by its file name). Returns an
// empty string on success, else an error naming the file.
std::string write_ros_map(const RosMap& map, const std::string& pgm_path, const std::string& yaml_path);

// Reads a map_server YAML and the PGM it names (relative to the YAML's folder). Errors name
// the file and, for the YAML, the line.
std::string read_ros_map(const std::string& yaml_path, RosMap& map);
// Reads a PGM (P5, 8 bit) onto a known geometry and thresholds (reachable.pgm beside a map).
std::string read_pgm_cells(const std::string& pgm_path, RosMap& map);

}  // namespace stereoscout::occupancy
