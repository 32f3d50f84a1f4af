#pragma once
// What the robot believed at one instant, for tracing a decision of the explorer after a run:
// the navigation grid it planned on at its last map rebuild (the filter's estimate's grid,
// classified: the ML particle's unless filter.estimate_lineage_margin; with the contact cells
// and the recent obstacle layer's cells the explorer stamps on top), the ML trajectory so far
// and the current plan.
// `stereoscout explore --snapshot-at T` writes them between two ticks, outside the loop's
// allocation scope, at the first tick at or after T, as snapshots/navigation-<T>.pgm + .yaml
// (map_server format: the known part of the navigation grid and a metre around it) and .png
// (the same, 5 pixels a cell, with the trajectory in blue, odometry in red, the plan in
// green) and -plan.csv (the plan's waypoints), and appends a line to snapshots/navigation.csv:
// T, the tick's time, the explorer's pose, state and goal, and the plan's length.

#include <string>
#include <vector>

#include "stereoscout/stack/stack.hpp"

namespace stereoscout::cli {

// Times in simulated seconds from the comma-separated list `text` ("800,1200.5"), ascending.
// False, with `error` naming the bad entry, on anything else.
bool parse_snapshot_times(const std::string& text, std::vector<double>& times, std::string& error);

// Empty string on success, else an error naming the file.
std::string write_navigation_snapshot(const stack::Stack& stack, const std::string& out, double requested_s);

}  // namespace stereoscout::cli
