// stereoscout eval-map: scores an occupancy map (map.yaml + map.pgm, ROS map_server format)
// against the simulator's ground truth and prints JSON (issue 6; named `stereoscout-eval map`
// there). Accuracy counts ground-truth cells the map knows; coverage needs --reachable.
#include <cstdio>

#include "arguments.hpp"
#include "commands.hpp"
#include "map_eval.hpp"

namespace stereoscout::cli {

int run_eval_map(int argc, char** argv) {
  Arguments arguments("eval-map",
                      "Compares an occupancy map with a ground-truth map (both ROS map_server YAML +\n"
                      "PGM; resolutions and origins may differ: each ground-truth cell is compared\n"
                      "with the map cell holding its centre) and prints JSON: accuracy of the cells\n"
                      "the map knows, precision and recall of occupied cells, and coverage of the\n"
                      "reachable free space (with --reachable, a PGM on the ground truth's grid).");
  arguments.option("map", "YAML", "the map to score (map.yaml)");
  arguments.option("gt", "YAML", "the ground-truth map (map.yaml of the simulator's world)");
  arguments.option("reachable", "PGM", "reachable free space on the ground truth's grid (reachable.pgm)");
  if (!arguments.parse(argc, argv)) {
    return arguments.exit_code();
  }
  if (!arguments.has("map") || !arguments.has("gt")) {
    std::fprintf(stderr, "stereoscout eval-map: need --map and --gt\n");
    return 2;
  }
  occupancy::RosMap map;
  occupancy::RosMap ground_truth;
  std::string error = occupancy::read_ros_map(arguments.get("map"), map);
  if (error.empty()) error = occupancy::read_ros_map(arguments.get("gt"), ground_truth);
  occupancy::RosMap reachable = ground_truth;
  if (error.empty() && arguments.has("reachable")) {
    error = occupancy::read_pgm_cells(arguments.get("reachable"), reachable);
    if (error.empty() && (reachable.geometry.width_cells != ground_truth.geometry.width_cells ||
                          reachable.geometry.height_cells != ground_truth.geometry.height_cells)) {
      error = arguments.get("reachable") + ": size differs from the ground truth " + arguments.get("gt");
    }
  }
  if (!error.empty()) {
    std::fprintf(stderr, "stereoscout eval-map: %s\n", error.c_str());
    return 1;
  }
  const MapEvaluation evaluation =
      evaluate_map(map, ground_truth, arguments.has("reachable") ? &reachable : nullptr);
  std::fputs(evaluation.to_json().c_str(), stdout);
  return 0;
}

}  // namespace stereoscout::cli
