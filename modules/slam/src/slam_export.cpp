#include "stereoscout/slam/slam_export.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <vector>

namespace stereoscout::slam {

std::string tum_line(std::int64_t timestamp_ns, const core::Pose2& pose) {
  const std::int64_t seconds = timestamp_ns / 1000000000;
  const std::int64_t nanoseconds = timestamp_ns % 1000000000;
  char line[160];
  std::snprintf(line, sizeof line, "%" PRId64 ".%09" PRId64 " %.6f %.6f 0 0 0 %.9f %.9f\n", seconds,
                nanoseconds < 0 ? -nanoseconds : nanoseconds, pose.x, pose.y, std::sin(0.5 * pose.theta),
                std::cos(0.5 * pose.theta));
  return line;
}

void write_tum_trajectory(std::ostream& out, const TrajectoryTree& tree, TrajectoryNodeHandle newest) {
  std::vector<TrajectoryNodeHandle> path;
  for (TrajectoryNodeHandle at = newest; at; at = tree.parent(at)) {
    path.push_back(at);
  }
  for (auto it = path.rbegin(); it != path.rend(); ++it) {
    const TrajectoryNode& node = tree.get(*it);
    out << tum_line(node.timestamp_ns, node.pose);
  }
}

std::size_t write_landmarks_ply(std::ostream& out, const LandmarkStore& store, const LandmarkMap& map,
                                std::uint32_t min_observations) {
  std::string vertices;
  std::size_t count = 0;
  store.for_each_estimate(map, [&](std::uint32_t id, const LandmarkEstimate& estimate) {
    if (estimate.observations < min_observations) {
      return;
    }
    char line[160];
    std::snprintf(line, sizeof line, "%.6f %.6f %.6f %u %u\n", estimate.mean.x(), estimate.mean.y(),
                  estimate.mean.z(), id, estimate.observations);
    vertices += line;
    ++count;
  });
  out << "ply\nformat ascii 1.0\ncomment stereoscout landmarks of the maximum-likelihood particle\n"
      << "element vertex " << count << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property uint landmark_id\nproperty uint observations\nend_header\n"
      << vertices;
  return count;
}

}  // namespace stereoscout::slam
