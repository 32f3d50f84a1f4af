#include "stereoscout/explore/seen_obstacles.hpp"

namespace stereoscout::explore {

std::size_t seen_obstacles_from_scan(const core::DepthScan& scan, const core::Pose2& pose, ScanObstacles which,
                                     Eigen::Vector2d* points, std::size_t capacity) {
  const bool camera_height_only = which == ScanObstacles::at_camera_height;
  std::size_t count = 0;
  for (const core::DepthScanColumn& column : scan.columns) {
    if (count == capacity) break;
    if (column.kind != core::DepthScanColumn::Kind::obstacle) continue;
    if (camera_height_only && !column.obstacle_at_camera_height) continue;
    points[count++] = pose.transform_point(Eigen::Vector2d(column.x_robot_m, column.y_robot_m));
  }
  return count;
}

}  // namespace stereoscout::explore
