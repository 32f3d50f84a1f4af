#pragma once
// The ancestry of every particle as a reference-counted tree (paper Fig. 3): one node per
// particle per update, holding the pose the particle had after that update and a link to
// its parent. A particle holds one reference to its newest node, each node one reference to
// its parent, so a node lives exactly as long as some particle descends from it (or another
// module retains it).
//
// For the just-in-time occupancy grid (next issue): find the ML particle's node
// (ParticleFilter::ml_trajectory_node), walk parent() towards the root to the nearest node
// whose user_slot names a grid, then roll the stored depth scans up along the path back to
// the present. A module that attaches data to a node stores a small index in user_slot,
// retains the node for as long as it keeps the data, and may register a free listener to
// hear when a node it tagged is gone.

#include <cstddef>
#include <cstdint>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/shared_pool.hpp"

namespace stereoscout::slam {

struct TrajectoryNode;
using TrajectoryNodeHandle = core::Handle<TrajectoryNode>;

// user_slot value meaning "no data attached".
inline constexpr std::uint32_t kNoUserSlot = 0xFFFFFFFFU;

struct TrajectoryNode {
  core::Pose2 pose;                     // map frame, after this update
  std::int64_t timestamp_ns = 0;        // odometry time of the update
  std::uint32_t update_index = 0;       // filter update that made the node
  std::uint32_t user_slot = kNoUserSlot;  // owned by whichever module attached data
  TrajectoryNodeHandle parent;          // null at the root
};

class TrajectoryTree {
 public:
  // Called with the node just before it is freed (its user_slot still readable).
  using FreeListener = void (*)(void* context, const TrajectoryNode& node);

  explicit TrajectoryTree(std::size_t capacity) : nodes_(capacity) {}

  TrajectoryTree(const TrajectoryTree&) = delete;
  TrajectoryTree& operator=(const TrajectoryTree&) = delete;

  // A new node whose parent (may be null) gains a reference; the caller holds the new
  // node's first reference. Null when the pool is full (the pool counts it).
  TrajectoryNodeHandle add(TrajectoryNodeHandle parent, const core::Pose2& pose,
                           std::int64_t timestamp_ns, std::uint32_t update_index);

  void retain(TrajectoryNodeHandle node) { nodes_.retain(node); }
  // Drops one reference; frees the node and, in turn, ancestors nobody else holds.
  void release(TrajectoryNodeHandle node);

  const TrajectoryNode& get(TrajectoryNodeHandle node) const { return nodes_.get(node); }
  TrajectoryNodeHandle parent(TrajectoryNodeHandle node) const { return nodes_.get(node).parent; }
  // The node of `node`'s lineage made by update `update_index` (`node` itself if it is that
  // update's); null when the lineage has none (a refused update, or it starts later).
  TrajectoryNodeHandle ancestor_at(TrajectoryNodeHandle node, std::uint32_t update_index) const;
  // Whether `node` is `ancestor` or descends from it.
  bool descends_from(TrajectoryNodeHandle node, TrajectoryNodeHandle ancestor) const {
    return ancestor && ancestor_at(node, get(ancestor).update_index) == ancestor;
  }
  std::uint32_t use_count(TrajectoryNodeHandle node) const { return nodes_.use_count(node); }
  bool is_live(TrajectoryNodeHandle node) const { return nodes_.is_live(node); }
  void set_user_slot(TrajectoryNodeHandle node, std::uint32_t slot) { nodes_.get(node).user_slot = slot; }
  void set_free_listener(FreeListener listener, void* context) {
    listener_ = listener;
    listener_context_ = context;
  }

  std::size_t in_use() const { return nodes_.in_use(); }
  std::size_t available() const { return nodes_.capacity() - nodes_.in_use(); }
  core::PoolStats stats() const { return nodes_.stats(); }

 private:
  core::SharedPool<TrajectoryNode> nodes_;
  FreeListener listener_ = nullptr;
  void* listener_context_ = nullptr;
};

}  // namespace stereoscout::slam
