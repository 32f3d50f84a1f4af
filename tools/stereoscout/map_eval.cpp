#include "map_eval.hpp"

#include <cmath>
#include <cstdio>

namespace stereoscout::cli {
namespace {

using occupancy::CellState;

CellState map_state_at(const occupancy::RosMap& map, double x_m, double y_m) {
  const double fx = std::floor((x_m - map.geometry.origin_x_m) / map.geometry.resolution_m);
  const double fy = std::floor((y_m - map.geometry.origin_y_m) / map.geometry.resolution_m);
  if (!(fx >= 0.0 && fy >= 0.0 && fx < map.geometry.width_cells && fy < map.geometry.height_cells)) {
    return CellState::unknown;
  }
  return map.at(static_cast<int>(fx), static_cast<int>(fy));
}

}  // namespace

MapEvaluation evaluate_map(const occupancy::RosMap& map, const occupancy::RosMap& ground_truth,
                           const occupancy::RosMap* reachable) {
  MapEvaluation result;
  result.has_reachable = reachable != nullptr;
  const occupancy::GridGeometry& gt = ground_truth.geometry;
  for (int y = 0; y < gt.height_cells; ++y) {
    for (int x = 0; x < gt.width_cells; ++x) {
      const double centre_x = gt.origin_x_m + (x + 0.5) * gt.resolution_m;
      const double centre_y = gt.origin_y_m + (y + 0.5) * gt.resolution_m;
      const CellState estimate = map_state_at(map, centre_x, centre_y);
      const CellState truth = ground_truth.at(x, y);
      if (reachable != nullptr && reachable->at(x, y) == CellState::free) {
        ++result.reachable;
        if (estimate == CellState::free) ++result.reachable_known_free;
      }
      if (truth == CellState::unknown) continue;
      ++result.ground_truth_known;
      if (truth == CellState::occupied) ++result.ground_truth_occupied;
      if (estimate == CellState::unknown) continue;
      ++result.compared;
      if (estimate == truth) ++result.correct;
      if (estimate == CellState::occupied) {
        ++result.map_occupied;
        if (truth == CellState::occupied) ++result.true_occupied;
      }
    }
  }
  return result;
}

std::string MapEvaluation::to_json() const {
  char buffer[1024];
  std::snprintf(buffer, sizeof(buffer),
                "{\n  \"accuracy_of_known_cells\": %.6f,\n  \"occupied_precision\": %.6f,\n"
                "  \"occupied_recall\": %.6f,\n  \"coverage\": %s,\n  \"ground_truth_known_cells\": %llu,\n"
                "  \"compared_cells\": %llu,\n  \"correct_cells\": %llu,\n  \"map_occupied_cells\": %llu,\n"
                "  \"true_occupied_cells\": %llu,\n  \"ground_truth_occupied_cells\": %llu,\n"
                "  \"reachable_cells\": %llu,\n  \"reachable_known_free_cells\": %llu,\n"
                "  \"sampling\": \"each ground-truth cell against the map cell holding its centre\"\n}\n",
                accuracy(), occupied_precision(), occupied_recall(),
                has_reachable ? std::to_string(coverage()).c_str() : "null",
                static_cast<unsigned long long>(ground_truth_known), static_cast<unsigned long long>(compared),
                static_cast<unsigned long long>(correct), static_cast<unsigned long long>(map_occupied),
                static_cast<unsigned long long>(true_occupied),
                static_cast<unsigned long long>(ground_truth_occupied), static_cast<unsigned long long>(reachable),
                static_cast<unsigned long long>(reachable_known_free));
  return buffer;
}

}  // namespace stereoscout::cli
