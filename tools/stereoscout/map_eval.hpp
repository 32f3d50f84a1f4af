#pragma once
// Scores an occupancy map against a ground-truth map (ROS map_server files), for
// `stereoscout eval-map`. The two may differ in resolution and origin: every ground-truth
// cell is compared with the map cell that contains its centre (outside the map = unknown).

#include <cstdint>
#include <string>

#include "stereoscout/occupancy/ros_map.hpp"

namespace stereoscout::cli {

struct MapEvaluation {
  std::uint64_t ground_truth_known = 0;    // ground-truth cells free or occupied
  std::uint64_t compared = 0;              // ... that the map also knows
  std::uint64_t correct = 0;               // ... and classifies the same
  std::uint64_t map_occupied = 0;          // compared cells the map calls occupied
  std::uint64_t true_occupied = 0;         // ... that are occupied in the ground truth
  std::uint64_t ground_truth_occupied = 0;
  std::uint64_t reachable = 0;             // reachable free cells (when given)
  std::uint64_t reachable_known_free = 0;  // ... that the map calls free
  bool has_reachable = false;

  double accuracy() const { return ratio(correct, compared); }
  double occupied_precision() const { return ratio(true_occupied, map_occupied); }
  double occupied_recall() const { return ratio(true_occupied, ground_truth_occupied); }
  double coverage() const { return ratio(reachable_known_free, reachable); }
  std::string to_json() const;

 private:
  static double ratio(std::uint64_t a, std::uint64_t b) {
    return b == 0 ? 0.0 : static_cast<double>(a) / static_cast<double>(b);
  }
};

// reachable: null, or free cells = reachable space, on the ground truth's geometry.
MapEvaluation evaluate_map(const occupancy::RosMap& map, const occupancy::RosMap& ground_truth,
                           const occupancy::RosMap* reachable);

}  // namespace stereoscout::cli
