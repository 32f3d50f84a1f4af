#pragma once
// Files a run leaves behind (design.md section 4): trajectories in the TUM format and the
// ML particle's landmark map as ASCII PLY. Written after a run or on request, never in the
// tick loop (they allocate).

#include <cstdint>
#include <ostream>
#include <string>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/slam/landmark_map.hpp"
#include "stereoscout/slam/trajectory_tree.hpp"

namespace stereoscout::slam {

// One TUM line "t x y z qx qy qz qw" for a floor pose (z = 0, rotation about z).
std::string tum_line(std::int64_t timestamp_ns, const core::Pose2& pose);

// The trajectory that ends at `newest`: its ancestors oldest first, one TUM line each.
void write_tum_trajectory(std::ostream& out, const TrajectoryTree& tree, TrajectoryNodeHandle newest);

// Estimates with at least `min_observations` observations, as PLY vertices with x, y, z,
// landmark_id and observations. Returns the number of vertices written.
std::size_t write_landmarks_ply(std::ostream& out, const LandmarkStore& store, const LandmarkMap& map,
                                std::uint32_t min_observations);

}  // namespace stereoscout::slam
