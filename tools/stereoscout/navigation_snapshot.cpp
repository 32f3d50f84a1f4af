#include "navigation_snapshot.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "map_png.hpp"
#include "run_directory.hpp"
#include "stereoscout/occupancy/ros_map.hpp"

namespace stereoscout::cli {
namespace {

// The files hold the known part of the grid and this many cells around it; the picture shows
// each cell as a square of this many pixels.
constexpr int kMarginCells = 10;
constexpr int kPixelsPerCell = 5;

occupancy::RosMap navigation_map_of(const explore::GridView& view) {
  occupancy::RosMap map;
  map.geometry.width_cells = view.width;
  map.geometry.height_cells = view.height;
  map.geometry.resolution_m = view.resolution_m;
  map.geometry.origin_x_m = view.origin_m.x();
  map.geometry.origin_y_m = view.origin_m.y();
  map.cells.resize(map.geometry.cell_count());
  for (std::size_t i = 0; i < map.cells.size(); ++i) map.cells[i] = static_cast<occupancy::CellState>(view.cells[i]);
  return map;
}

// The bounding box of the known cells, grown by `margin` cells (the whole grid if none is known).
occupancy::RosMap cropped_to_known(const occupancy::RosMap& map, int margin) {
  const occupancy::GridGeometry& g = map.geometry;
  int x0 = g.width_cells;
  int y0 = g.height_cells;
  int x1 = -1;
  int y1 = -1;
  for (int y = 0; y < g.height_cells; ++y) {
    for (int x = 0; x < g.width_cells; ++x) {
      if (map.at(x, y) == occupancy::CellState::unknown) continue;
      x0 = std::min(x0, x);
      y0 = std::min(y0, y);
      x1 = std::max(x1, x);
      y1 = std::max(y1, y);
    }
  }
  if (x1 < 0) return map;
  x0 = std::max(0, x0 - margin);
  y0 = std::max(0, y0 - margin);
  x1 = std::min(g.width_cells - 1, x1 + margin);
  y1 = std::min(g.height_cells - 1, y1 + margin);
  occupancy::RosMap crop;
  crop.geometry = g;
  crop.geometry.width_cells = x1 - x0 + 1;
  crop.geometry.height_cells = y1 - y0 + 1;
  crop.geometry.origin_x_m = g.origin_x_m + x0 * g.resolution_m;
  crop.geometry.origin_y_m = g.origin_y_m + y0 * g.resolution_m;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) crop.cells.push_back(map.at(x, y));
  }
  return crop;
}

// Each cell as `factor` x `factor` cells, so that the drawn paths are thinner than a cell.
occupancy::RosMap magnified(const occupancy::RosMap& map, int factor) {
  occupancy::RosMap large;
  large.geometry = map.geometry;
  large.geometry.width_cells *= factor;
  large.geometry.height_cells *= factor;
  large.geometry.resolution_m /= factor;
  large.cells.reserve(large.geometry.cell_count());
  for (int y = 0; y < large.geometry.height_cells; ++y) {
    for (int x = 0; x < large.geometry.width_cells; ++x) large.cells.push_back(map.at(x / factor, y / factor));
  }
  return large;
}

std::string append_summary(const stack::Stack& stack, const std::string& path, double requested_s) {
  const bool is_new = !std::filesystem::exists(path);
  std::FILE* file = std::fopen(path.c_str(), "a");
  if (file == nullptr) return path + ": cannot write";
  if (is_new) std::fprintf(file, "requested_s,time_s,x_m,y_m,theta_rad,state,goal_x_m,goal_y_m,plan_waypoints\n");
  const core::Pose2 pose = stack.current_pose();
  const explore::Explorer& explorer = stack.explorer();
  std::fprintf(file, "%.2f,%.2f,%.3f,%.3f,%.4f,%s,%.3f,%.3f,%zu\n", requested_s, stack.time_s(), pose.x, pose.y, pose.theta,
               explore::to_string(explorer.state()), explorer.goal().position.x(), explorer.goal().position.y(),
               explorer.plan().waypoints.size());
  const bool written = std::fclose(file) == 0;
  return written ? std::string() : path + ": cannot write";
}

// The current plan, one waypoint a line, in the map frame: where the follower was steering.
std::string write_plan_csv(const explore::Plan& plan, const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) return path + ": cannot write";
  std::fprintf(file, "x_m,y_m,narrow\n");
  for (std::size_t k = 0; k < plan.waypoints.size(); ++k) {
    std::fprintf(file, "%.3f,%.3f,%d\n", plan.waypoints[k].x(), plan.waypoints[k].y(), plan.narrow[k] ? 1 : 0);
  }
  const bool written = std::fclose(file) == 0;
  return written ? std::string() : path + ": cannot write";
}

}  // namespace

bool parse_snapshot_times(const std::string& text, std::vector<double>& times, std::string& error) {
  times.clear();
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string entry = text.substr(begin, end - begin);
    char* parsed_end = nullptr;
    errno = 0;
    const double time_s = std::strtod(entry.c_str(), &parsed_end);
    if (entry.empty() || errno != 0 || *parsed_end != '\0' || !std::isfinite(time_s) || time_s < 0.0) {
      error = "'" + entry + "' is not a time in seconds (a list such as 800,1200.5)";
      return false;
    }
    times.push_back(time_s);
    begin = end + 1;
  }
  std::sort(times.begin(), times.end());
  return true;
}

std::string write_navigation_snapshot(const stack::Stack& stack, const std::string& out, double requested_s) {
  const std::string folder = out + "/snapshots";
  std::error_code ignored;
  std::filesystem::create_directories(folder, ignored);
  char stem[64];
  std::snprintf(stem, sizeof stem, "/navigation-%.1f", requested_s);
  const std::string base = folder + stem;
  // What the explorer planned on at its last rebuild: the estimate's grid with the contact
  // cells and the recent obstacle layer's cells occupied (its own copy when there are any).
  const explore::GridView& planned_on = stack.explorer().navigation_map().grid();
  const occupancy::RosMap map =
      cropped_to_known(navigation_map_of(planned_on.cells != nullptr ? planned_on : stack.grid_view()), kMarginCells);
  std::string error = occupancy::write_ros_map(map, base + ".pgm", base + ".yaml");
  if (error.empty()) error = write_map_png(magnified(map, kPixelsPerCell), map_overlays(stack), base + ".png");
  if (error.empty()) error = write_plan_csv(stack.explorer().plan(), base + "-plan.csv");
  if (error.empty()) error = append_summary(stack, folder + "/navigation.csv", requested_s);
  return error;
}

}  // namespace stereoscout::cli
