#include "stereoscout/explore/seen_obstacles.hpp"

namespace stereoscout::explore {

std::size_t seen_obstacles_from_scan(const core::DepthScan& scan, const core::Pose2& pose, Eigen::Vector2d* points,
                                     std::size_t capacity) {
  std::size_t count = 0;
  for (const core::DepthScanColumn& column : scan.columns) {
    if (count == capacity) break;
    if (column.kind != core::DepthScanColumn::Kind::obstacle || !column.obstacle_at_camera_height) continue;
    points[count++] = pose.transform_point(Eigen::Vector2d(column.x_robot_m, column.y_robot_m));
  }
  return count;
}

}  // namespace stereoscout::explore
