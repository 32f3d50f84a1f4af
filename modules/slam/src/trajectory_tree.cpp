#include "stereoscout/slam/trajectory_tree.hpp"

namespace stereoscout::slam {

TrajectoryNodeHandle TrajectoryTree::add(TrajectoryNodeHandle parent, const core::Pose2& pose,
                                         std::int64_t timestamp_ns, std::uint32_t update_index) {
  TrajectoryNode node;
  node.pose = pose;
  node.timestamp_ns = timestamp_ns;
  node.update_index = update_index;
  node.parent = parent;
  const TrajectoryNodeHandle handle = nodes_.acquire(node);
  if (handle && parent) {
    nodes_.retain(parent);
  }
  return handle;
}

TrajectoryNodeHandle TrajectoryTree::ancestor_at(TrajectoryNodeHandle node, std::uint32_t update_index) const {
  while (node && get(node).update_index > update_index) node = parent(node);
  return node && get(node).update_index == update_index ? node : TrajectoryNodeHandle{};
}

void TrajectoryTree::release(TrajectoryNodeHandle node) {
  // Iterative, not recursive: a lineage can be thousands of updates long.
  while (node) {
    TrajectoryNodeHandle parent;
    const bool freed = nodes_.release(node, [&](TrajectoryNode& dying) {
      parent = dying.parent;
      if (listener_ != nullptr) {
        listener_(listener_context_, dying);
      }
    });
    if (!freed) {
      return;
    }
    node = parent;
  }
}

}  // namespace stereoscout::slam
