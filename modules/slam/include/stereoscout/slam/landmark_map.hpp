#pragma once
// The landmark maps of all particles: FastSLAM's persistent balanced tree keyed by landmark
// identity (paper III; Montemerlo et al.), with path copying over reference-counted pools so
// that particles share every subtree neither has changed since they became siblings.
//
// The tree is a trie with 8 children per node over the identity written in base 8: a map of
// depth d holds ids in [0, 8^d), its leaves sit at level d and the path to an id follows its
// base-8 digits from the most significant one. The descriptor index hands out dense,
// increasing ids, so the trie is a balanced tree of depth ceil(log8 K) for K identities (5 for
// 10,000: a third of the binary trie's depth, so a third of the nodes to copy per change), and
// it grows a new root (one level) whenever an id needs one more digit. A node is one cache
// line. The leaf of an id holds a short list of spatially distinct 3D Gaussian estimates
// (paper Fig. 1), each itself shared between particles.
//
// Ownership: a LandmarkMap value holds one reference to its root; retain()/release() add or
// drop whole-map references; mutable_leaf() copies exactly the shared nodes on the path to
// one id. All memory comes from two CountedPools sized at start-up; when they run short the
// change is refused up front (never half-done) and counted.

#include <cstddef>
#include <cstdint>

#include <Eigen/Core>

#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/slam/counted_pool.hpp"

namespace stereoscout::slam {

// Most estimates one identity can hold; config filter.estimates_per_landmark picks the
// working limit at or below it.
inline constexpr std::size_t kMaxEstimatesPerLandmark = 4;

// Children per trie node and the id bits one level consumes.
inline constexpr unsigned kTrieDigitBits = 3;
inline constexpr unsigned kTrieFanout = 1U << kTrieDigitBits;

// A symmetric 3x3 matrix kept as its upper triangle: 6 doubles instead of 9, so an estimate
// is 80 bytes instead of 104 and the filter's 3x3 algebra works on the 6 distinct entries.
// Converting from and to Eigen is exact.
struct SymmetricMatrix3 {
  double xx = 1.0, xy = 0.0, xz = 0.0, yy = 1.0, yz = 0.0, zz = 1.0;  // identity

  SymmetricMatrix3() = default;
  SymmetricMatrix3(double xx_, double xy_, double xz_, double yy_, double yz_, double zz_)
      : xx(xx_), xy(xy_), xz(xz_), yy(yy_), yz(yz_), zz(zz_) {}
  // From any 3x3 Eigen expression, keeping its upper triangle (every covariance the filter
  // stores is symmetric: it comes from core::symmetrize() or from this type's own algebra).
  template <class Derived>
  SymmetricMatrix3(const Eigen::MatrixBase<Derived>& m)  // implicit, like assigning a Matrix3d
      : xx(m(0, 0)), xy(m(0, 1)), xz(m(0, 2)), yy(m(1, 1)), yz(m(1, 2)), zz(m(2, 2)) {}

  double operator()(Eigen::Index row, Eigen::Index col) const {
    const Eigen::Index low = row < col ? row : col;
    const Eigen::Index high = row < col ? col : row;
    if (low == 0) {
      return high == 0 ? xx : (high == 1 ? xy : xz);
    }
    return low == 1 ? (high == 1 ? yy : yz) : zz;
  }
  Eigen::Matrix3d full() const {
    Eigen::Matrix3d m;
    m << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    return m;
  }
};

// A 3D Gaussian estimate of one landmark in the map frame.
struct LandmarkEstimate {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  SymmetricMatrix3 covariance;
  std::uint32_t observations = 0;  // observations fused into it, the first included
};

struct MapNode;
using MapNodeHandle = PoolIndex<MapNode>;
using EstimateHandle = PoolIndex<LandmarkEstimate>;

// One node of the trie, one cache line: interior nodes use `child`, leaves use `estimates`.
struct alignas(64) MapNode {
  MapNodeHandle child[kTrieFanout] = {};
  core::StaticVector<EstimateHandle, kMaxEstimatesPerLandmark> estimates;
};

// One particle's map: a root reference and the trie depth (ids below 8^depth).
struct LandmarkMap {
  MapNodeHandle root;
  std::uint8_t depth = 0;
};

struct LandmarkStoreCounters {
  std::uint64_t path_nodes_copied = 0;     // shared nodes copied by path copying
  std::uint64_t estimates_copied = 0;      // shared estimates copied before an update
  std::uint64_t refused_pool_full = 0;     // changes refused because a pool was short
};

class LandmarkStore {
 public:
  LandmarkStore(std::size_t node_capacity, std::size_t estimate_capacity);

  LandmarkStore(const LandmarkStore&) = delete;
  LandmarkStore& operator=(const LandmarkStore&) = delete;

  // Whole-map references (a particle copied by resampling retains; a dropped one releases).
  void retain(const LandmarkMap& map);
  void release(LandmarkMap& map);

  // The leaf of `id`, or nullptr when the map has never seen it. Read-only, never copies.
  const MapNode* find_leaf(const LandmarkMap& map, std::uint32_t id) const;

  // The leaf of `id`, made exclusive to `map` by copying the shared nodes on its path (and
  // creating the missing ones). Its estimate handles may still be shared: use
  // mutable_estimate() before changing one. Returns nullptr, counted, when the pools cannot
  // hold the worst case of this change plus `estimates_needed` new estimates; the map is
  // then unchanged.
  MapNode* mutable_leaf(LandmarkMap& map, std::uint32_t id, std::size_t estimates_needed);

  // Estimate `index` of an exclusive leaf, copied first if another leaf shares it. Call
  // only after mutable_leaf(..., estimates_needed >= 1) succeeded for this leaf.
  LandmarkEstimate& mutable_estimate(MapNode& leaf, std::size_t index);
  // Adds a new estimate to an exclusive, non-full leaf (pool room checked by mutable_leaf).
  LandmarkEstimate& add_estimate(MapNode& leaf, const LandmarkEstimate& estimate);

  const LandmarkEstimate& estimate(EstimateHandle handle) const { return estimates_.get(handle); }
  const MapNode& node(MapNodeHandle handle) const { return nodes_.get(handle); }
  std::uint32_t use_count(MapNodeHandle handle) const { return nodes_.use_count(handle); }
  std::uint32_t use_count(EstimateHandle handle) const { return estimates_.use_count(handle); }

  // Visits every (id, estimate) of a map in increasing id order, list order within an id.
  template <class Visitor>
  void for_each_estimate(const LandmarkMap& map, Visitor&& visit) const {
    if (map.root) {
      visit_subtree(map.root, map.depth, 0, visit);
    }
  }

  std::size_t nodes_in_use() const { return nodes_.in_use(); }
  std::size_t estimates_in_use() const { return estimates_.in_use(); }
  core::PoolStats node_stats() const { return nodes_.stats(); }
  core::PoolStats estimate_stats() const { return estimates_.stats(); }
  const LandmarkStoreCounters& counters() const { return counters_; }

 private:
  template <class Visitor>
  void visit_subtree(MapNodeHandle handle, unsigned levels_below, std::uint32_t id_prefix,
                     Visitor& visit) const {
    const MapNode& n = nodes_.get(handle);
    if (levels_below == 0) {
      for (const EstimateHandle e : n.estimates) {
        visit(id_prefix, estimates_.get(e));
      }
      return;
    }
    for (std::uint32_t digit = 0; digit < kTrieFanout; ++digit) {
      if (n.child[digit]) {
        visit_subtree(n.child[digit], levels_below - 1, (id_prefix << kTrieDigitBits) | digit, visit);
      }
    }
  }

  void release_node(MapNodeHandle handle);
  MapNodeHandle copy_for_path(MapNodeHandle source, unsigned level, unsigned path_digit);

  CountedPool<MapNode> nodes_;
  CountedPool<LandmarkEstimate> estimates_;
  LandmarkStoreCounters counters_;
};

// Bits needed to write `id` (0 for id 0).
unsigned bits_for_id(std::uint32_t id);
// Base-8 digits needed to write `id` (0 for id 0): the depth a map needs to hold it.
unsigned levels_for_id(std::uint32_t id);
// The digit of `id` that picks the child of a node `level` levels above the leaves.
inline unsigned trie_digit(std::uint32_t id, unsigned level) {
  return level == 0 ? 0U : (id >> ((level - 1) * kTrieDigitBits)) & (kTrieFanout - 1);
}

}  // namespace stereoscout::slam
