#pragma once
// Config section `vision`: SIFT front end, stereo matching, descriptor index, 2.5D scan
// (paper sections IV and V).
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

struct VisionConfig {
  int max_features = 1000;
  double sigma_u_px = 10.0;
  double sigma_v_px = 10.0;
  double sigma_d_px = 0.5;
  double epipolar_tolerance_px = 2.0;
  double min_disparity_px = 1.0;
  double max_disparity_px = 128.0;
  double match_ratio = 0.8;
  int index_capacity = 100000;
  int candidate_min_frames = 3;
  int index_max_leaf_checks = 64;
  double floor_tolerance_m = 0.05;
  double scan_max_range_m = 6.0;
};

inline void describe(ConfigVisitor& v, VisionConfig& c) {
  v.begin_section("vision", "SIFT landmarks, stereo triangulation, descriptor index and the 2.5D obstacle scan (paper IV, V).");
  v.integer_field("max_features", c.max_features, {16, 20000, "", "Most SIFT keypoints kept per image."});
  v.number("sigma_u_px", c.sigma_u_px, {0.01, 100.0, "px", "Column noise of a stereo point (paper 10)."});
  v.number("sigma_v_px", c.sigma_v_px, {0.01, 100.0, "px", "Row noise of a stereo point (paper 10)."});
  v.number("sigma_d_px", c.sigma_d_px, {0.01, 20.0, "px", "Disparity noise of a stereo point (paper 0.5)."});
  v.number("epipolar_tolerance_px", c.epipolar_tolerance_px, {0.0, 20.0, "px", "Largest row difference between left and right keys of a match."});
  v.number("min_disparity_px", c.min_disparity_px, {0.1, 1000.0, "px", "Smallest disparity accepted (bounds the farthest point)."});
  v.number("max_disparity_px", c.max_disparity_px, {1.0, 1000.0, "px", "Largest disparity accepted (bounds the nearest point)."});
  v.number("match_ratio", c.match_ratio, {0.1, 1.0, "", "Distinctiveness test: best distance below this times the second best."});
  v.integer_field("index_capacity", c.index_capacity, {16, 10000000, "", "Descriptors the index holds (landmarks and candidates)."});
  v.integer_field("candidate_min_frames", c.candidate_min_frames, {1, 100, "frames", "A new key becomes a landmark after being seen in this many frames."});
  v.integer_field("index_max_leaf_checks", c.index_max_leaf_checks, {1, 100000, "", "Best-bin-first search: leaves examined per query."});
  v.number("floor_tolerance_m", c.floor_tolerance_m, {0.0, 1.0, "m", "Points higher than this above the floor count as obstacles in the 2.5D scan."});
  v.number("scan_max_range_m", c.scan_max_range_m, {0.5, 50.0, "m", "Farthest range the 2.5D scan reports."});
  v.require(c.min_disparity_px < c.max_disparity_px, "max_disparity_px", "must be larger than min_disparity_px");
  v.end_section();
}

}  // namespace stereoscout::core
