#include "navigation_snapshot.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "map_png.hpp"
#include "stereoscout/occupancy/ros_map.hpp"

namespace stereoscout::cli {
namespace {

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

MapOverlays overlays_of(const stack::Stack& stack) {
  MapOverlays overlays;
  const slam::ParticleFilter& filter = stack.filter();
  for (slam::TrajectoryNodeHandle n = filter.ml_trajectory_node(); n; n = filter.trajectory().parent(n)) {
    overlays.estimated_trajectory.push_back(filter.trajectory().get(n).pose.translation());
  }
  std::reverse(overlays.estimated_trajectory.begin(), overlays.estimated_trajectory.end());
  for (const core::Pose2& pose : stack.odometry_path()) overlays.raw_odometry.push_back(pose.translation());
  for (const Eigen::Vector2d& waypoint : stack.explorer().plan().waypoints) overlays.plan.push_back(waypoint);
  return overlays;
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
  const occupancy::RosMap map = navigation_map_of(stack.grid_view());
  std::string error = occupancy::write_ros_map(map, base + ".pgm", base + ".yaml");
  if (error.empty()) error = write_map_png(map, overlays_of(stack), base + ".png");
  if (error.empty()) error = append_summary(stack, folder + "/navigation.csv", requested_s);
  return error;
}

}  // namespace stereoscout::cli
