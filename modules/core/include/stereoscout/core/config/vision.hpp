#pragma once
// Config section `vision`: SIFT front end, stereo matching, descriptor index, 2.5D scan
// (paper sections IV and V).
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

struct VisionConfig {
  int max_features = 500;
  double sigma_u_px = 10.0;
  double sigma_v_px = 10.0;
  double sigma_d_px = 0.5;
  double epipolar_tolerance_px = 2.0;
  double min_disparity_px = 1.0;
  double max_disparity_px = 128.0;
  double match_ratio = 0.8;
  bool stereo_cross_check = true;
  int index_capacity = 400000;
  int candidate_min_frames = 3;
  int index_max_leaf_checks = 64;
  double floor_tolerance_m = 0.05;
  double scan_max_range_m = 6.0;
  // SIFT detector (Lowe's defaults, which OpenCV also uses).
  int sift_octave_layers = 3;
  double sift_contrast_threshold = 0.04;
  double sift_edge_threshold = 10.0;
  double sift_sigma = 1.6;
  bool sift_parallel = true;
  // The dense disparity and the scan on a thread of their own in the observation update.
  bool scan_parallel = true;
  // Descriptor index.
  double index_match_distance = 180.0;
  int index_bucket_size = 16;
  bool index_box_distance = false;
  // Identities split by where their points lie (IdentityGate).
  bool identity_gate = false;
  int identity_gate_instances = 400000;
  int identity_gate_instances_per_identity = 32;
  // Dense disparity block matcher.
  int dense_num_disparities = 64;
  int dense_window_px = 7;
  double dense_uniqueness_ratio = 0.1;
  double dense_min_texture = 2.5;
  int dense_lr_tolerance_px = 1;
  int dense_speckle_max_region_px = 100;
  double dense_speckle_max_step_px = 1.0;
  double dense_speckle_min_area_m2 = 0.0025;
  double dense_speckle_area_apart_px = 3.0;
  int scan_min_obstacle_pixels = 4;
  double scan_same_surface_depth_m = 0.15;
  double scan_blank_wall_within_m = 1.5;
  double scan_blank_wall_untextured_fraction = 0.5;
  double scan_wall_base_min_step = 12.0;
  double scan_wall_base_within_m = 3.5;
  bool scan_floor_onto_plane = true;
  int scan_near_min_matches = 0;
  double scan_near_max_dense_valid = 0.4;
  double scan_near_uniqueness = 0.7;
  int scan_near_window_px = 11;
};

inline void describe(ConfigVisitor& v, VisionConfig& c) {
  v.begin_section("vision", "SIFT landmarks, stereo triangulation, descriptor index and the 2.5D obstacle scan (paper IV, V).");
  v.integer_field("max_features", c.max_features, {16, 20000, "", "Most SIFT keypoints kept per image (the strongest). 500 keeps the simulated lab near the paper's landmark count per metre; 1000 filled the landmark pools and the index within 5 minutes (docs/results.md)."});
  v.number("sigma_u_px", c.sigma_u_px, {0.01, 100.0, "px", "Column noise of a stereo point (paper 10)."});
  v.number("sigma_v_px", c.sigma_v_px, {0.01, 100.0, "px", "Row noise of a stereo point (paper 10)."});
  v.number("sigma_d_px", c.sigma_d_px, {0.01, 20.0, "px", "Disparity noise of a stereo point (paper 0.5)."});
  v.number("epipolar_tolerance_px", c.epipolar_tolerance_px, {0.0, 20.0, "px", "Largest row difference between left and right keys of a match."});
  v.number("min_disparity_px", c.min_disparity_px, {0.1, 1000.0, "px", "Smallest disparity accepted (bounds the farthest point)."});
  v.number("max_disparity_px", c.max_disparity_px, {1.0, 1000.0, "px", "Largest disparity accepted (bounds the nearest point)."});
  v.number("match_ratio", c.match_ratio, {0.1, 1.0, "", "Distinctiveness test: best distance below this times the second best."});
  v.boolean("stereo_cross_check", c.stereo_cross_check, "Keep a stereo match only if the left key's best right key is the same key (mutual best; removes false matches on repetitive texture).");
  v.integer_field("index_capacity", c.index_capacity, {16, 10000000, "", "Descriptors the index holds (landmarks and candidates): a 25-minute exploration of the simulated lab needs about 200 000 (docs/results.md)."});
  v.integer_field("candidate_min_frames", c.candidate_min_frames, {1, 100, "frames", "A new key becomes a landmark after being seen in this many frames."});
  v.integer_field("index_max_leaf_checks", c.index_max_leaf_checks, {1, 100000, "", "Best-bin-first search: leaves examined per query."});
  v.number("floor_tolerance_m", c.floor_tolerance_m, {0.0, 1.0, "m", "Points higher than this above the floor count as obstacles in the 2.5D scan."});
  v.number("scan_max_range_m", c.scan_max_range_m, {0.5, 50.0, "m", "Farthest range the 2.5D scan reports."});
  v.integer_field("sift_octave_layers", c.sift_octave_layers, {1, 8, "", "SIFT scale layers per octave (Lowe 3)."});
  v.number("sift_contrast_threshold", c.sift_contrast_threshold, {0.001, 1.0, "", "SIFT rejects difference-of-Gaussian extrema weaker than this (Lowe 0.04)."});
  v.number("sift_edge_threshold", c.sift_edge_threshold, {1.0, 100.0, "", "SIFT rejects edge-like extrema with a curvature ratio above this (Lowe 10)."});
  v.number("sift_sigma", c.sift_sigma, {0.5, 5.0, "px", "Blur of the first SIFT octave (Lowe 1.6)."});
  v.boolean("sift_parallel", c.sift_parallel, "Run SIFT on the left and right image in two threads (results are identical to the sequential run).");
  v.boolean("scan_parallel", c.scan_parallel, "Run the dense disparity and the 2.5D scan of a kept pair on a thread of their own, beside SIFT and the filter update (results are identical to the sequential run). Off: one thread fewer, for a single-core computer.");
  v.number("index_match_distance", c.index_match_distance, {1.0, 1000.0, "", "Largest Euclidean distance between a key's descriptor and an index entry for the key to take that entry's identity (SIFT descriptors have norm 512)."});
  v.integer_field("index_bucket_size", c.index_bucket_size, {2, 256, "", "Descriptors in one KD-tree leaf before it splits."});
  v.boolean("index_box_distance", c.index_box_distance, "Best-bin-first search orders the tree's cells by their exact distance from the key (over every dimension the path to the cell splits), and stops at the match distance, where no entry can match. Off (the default): by the largest gap in any one dimension, a looser bound. On random descriptors the exact one needs fewer leaves for a key seen from the same place and finds a few more of the keys seen from elsewhere (vision_bench BM_IndexLookup, docs/results.md); not yet run in the whole stack.");
  v.boolean("identity_gate", c.identity_gate, "Split the index's identities by where their points lie in the odometry frame: a key whose point agrees with none of its identity's places (the filter's association gate, with the odometry's drift since, from the filter's linear motion-noise terms) becomes a landmark of its own. A look that repeats (floor tiles, a texture on several walls) otherwise names one landmark in many places. Off by default: the drift widens the gate over long drives, and with it the office's coverage fell (docs/results.md).");
  v.integer_field("identity_gate_instances", c.identity_gate_instances, {1, 10000000, "", "Landmarks the identity gate can make in all (each identity's places); when they run out, keys that need a new one are dropped (counted)."});
  v.integer_field("identity_gate_instances_per_identity", c.identity_gate_instances_per_identity, {1, 1024, "", "Places one index identity may name; a key of an identity with this many, agreeing with none, is dropped (counted)."});
  v.integer_field("dense_num_disparities", c.dense_num_disparities, {2, 512, "px", "Disparities searched by the dense block matcher (0 .. N-1). The nearest surface it measures lies focal * baseline / (N - 1) from the camera: 0.63 m at 64 on the default head, 0.42 m at 96, and most walker contacts came with the walker in view nearer than 0.63 m. 96 costs 29.4 ms a pair against 18.3 ms (AVX-512). With the 5 cm grid and far hits weighed (config/grid-5cm-near.yaml), 96 gave the lab and the clutter hall (three seeds each) no contact where 64 met the walker 4 times, and the office's six seeds 95.9% on the mean with 6 contacts (64: 97.6%, 5); at 10 cm it once shut clutter seed 2 in with near obstacle cells (docs/results.md, twenty-fourth, sixty-second and sixty-third sessions)."});
  v.integer_field("dense_window_px", c.dense_window_px, {1, 31, "px", "Side of the square window over which census costs are summed (odd)."});
  v.number("dense_uniqueness_ratio", c.dense_uniqueness_ratio, {0.0, 2.0, "", "A pixel is invalid unless the best cost times (1 + this) is below every non-adjacent disparity's cost."});
  v.number("dense_min_texture", c.dense_min_texture, {0.0, 255.0, "grey levels", "A pixel is invalid when the mean absolute horizontal central difference in its window is below this. Image noise of sigma s alone gives 2 s / sqrt(pi) = 1.13 s (the simulated camera, s = 2: 2.26), and census matching on such windows is random, so keep this above that for the camera in use (1 suits nearly noise-free images such as Middlebury's)."});
  v.integer_field("dense_lr_tolerance_px", c.dense_lr_tolerance_px, {0, 16, "px", "Left-right consistency: largest difference between the left and the right disparity."});
  v.integer_field("dense_speckle_max_region_px", c.dense_speckle_max_region_px, {0, 1000000, "px", "Speckle filter: a 4-connected region of similar disparities with at most this many pixels is marked invalid (scattered wrong matches on weak texture); 0 switches it off."});
  v.number("dense_speckle_max_step_px", c.dense_speckle_max_step_px, {0.0, 16.0, "px", "Speckle filter: neighbouring pixels whose disparities differ by at most this belong to one region."});
  v.number("dense_speckle_min_area_m2", c.dense_speckle_min_area_m2, {0.0, 1.0, "m^2", "Speckle filter: a region is also marked invalid when the surface it stands for, at the depth its disparities give, is smaller than this (pixels x (baseline / disparity)^2): look-alike book spines matched at a wrong, large disparity form regions of a few hundred pixels but a few square centimetres, phantom obstacles within a metre of the camera; 0 switches the rule off."});
  v.number("dense_speckle_area_apart_px", c.dense_speckle_area_apart_px, {0.0, 64.0, "px", "Speckle filter's area rule: a small region is removed only when no valid pixel around it (within its own width and height) has a disparity above the region's smallest less this. A wrong match stands in front of everything around it; a piece of a real near surface cut by holes (a brick wall's repeated courses) or into strips (seen at a slant) has pieces of the same surface beside it."});
  v.integer_field("scan_min_obstacle_pixels", c.scan_min_obstacle_pixels, {1, 100, "px", "Pixels of a column that must lie above the floor before the nearest of them counts as an obstacle (rejects isolated mismatches)."});
  v.number("scan_same_surface_depth_m", c.scan_same_surface_depth_m, {0.0, 2.0, "m", "How far behind a column's nearest obstacle point a point at the camera's height still counts as the same obstacle (a person's legs and chest, a wall's face); such an obstacle is in view at every range, so the grid clears its cell when a later view sees through it."});
  v.number("scan_blank_wall_within_m", c.scan_blank_wall_within_m, {0.0, 100.0, "m", "A column whose floor ends nearer than this with nothing seen beyond it (at any height) reports an obstacle where the floor ends: a blank wall gives stereo no disparity, and without this the robot drives into it. Farther out the floor's texture fades (the office's tiles at about 2 m), so its end is no wall there; 0 turns the rule off."});
  v.number("scan_blank_wall_untextured_fraction", c.scan_blank_wall_untextured_fraction, {0.0, 1.0, "", "The blank-wall rule also needs at least this fraction of the left image's pixels above the floor's end, up to the horizon, to have been rejected by the matcher for lack of texture: the floor can also end where stereo is confused (an occlusion edge beside a near object, a repeated pattern) with a textured, open view beyond it. 0: any floor end counts."});
  v.number("scan_wall_base_min_step", c.scan_wall_base_min_step, {0.0, 255.0, "grey levels", "A blank wall's base is where, down an image column from the horizon, the brightness of the rows above and below first steps by at least this much, with the run above it mostly untextured (scan_blank_wall_untextured_fraction); within scan_wall_base_within_m the scan puts the wall there, on the floor plane, rather than where the matched floor ends (0.3-0.6 m short of it, or nowhere when the wall is faced head-on). 0: the floor's end only."});
  v.number("scan_wall_base_within_m", c.scan_wall_base_within_m, {0.0, 100.0, "m", "How far out a blank wall's base (scan_wall_base_min_step) is looked for. Farther than the floor-end rule's scan_blank_wall_within_m: a corridor's blank walls are seen at a slant, 2-3.5 m ahead, and without hits from there the misses of the free columns ending at their base wear them away in the grid (the office's corridor walls: 20-40% of their cells held after a drive along it at 1.5 m, 97% at 3.5 m; docs/results.md). Beyond scan_blank_wall_within_m a base also needs floor matched in its column. 0: no wall base."});
  v.boolean("scan_floor_onto_plane", c.scan_floor_onto_plane, "A floor point that its disparity puts below the floor is moved up its pixel's ray to where that ray meets the floor plane: its disparity error alone put it farther (for the paper's 0.5 px, up to 8% of its range before the floor tolerance rejects it), and the farthest floor point of a column, its free end, is the one whose error put it farthest, beyond the wall behind it. The eval-scan sweep of the office: free rays through an obstacle 5736 -> 3644 (docs/results.md). Assumes a flat floor and a level camera, as the rest of the scan does.");
  v.integer_field("scan_near_min_matches", c.scan_near_min_matches, {0, 1000, "matches", "Surfaces nearer than the dense matcher reaches (focal * baseline / (dense_num_disparities - 1), 0.63 m from the camera on the default head) are taken from the SIFT stereo matches, which reach max_disparity_px (0.31 m): a match with a larger disparity than the dense matcher's, above the floor and below the robot, is an obstacle in its scan column when at least this many such matches (itself included) lie within scan_same_surface_depth_m of it on the floor. Without it the scan holds nothing that near: a low box's corner that came into view 0.4 m from the camera as the robot turned beside it was driven into (docs/results.md, clutter seed 3). 0 = off. Not in the paper."});
  v.number("scan_near_max_dense_valid", c.scan_near_max_dense_valid, {0.0, 1.0, "", "scan_near_min_matches counts a match only where at most this fraction of the dense disparities in the scan_near_window_px square around it are valid: a surface nearer than the dense matcher reaches leaves it nothing to match there (at clutter seed 3's box corner 0-31% of the window was valid), while most sparse matches with a disparity that large are a repeated texture matched a period off, over a surface the dense matcher did find (mostly 100% valid; about ten such matches a frame in the simulated clutter hall)."});
  v.number("scan_near_uniqueness", c.scan_near_uniqueness, {0.0, 1.0, "", "scan_near_min_matches counts a match only where the sum of absolute differences of the scan_near_window_px square patch around it, between the left image and the right at its disparity (give or take a pixel), is below this fraction of the smallest at every disparity the dense matcher covers: a near surface has nothing like it in that range, a repeated texture (which the dense matcher also leaves holes in, for its ambiguity) matches a period nearer too."});
  v.integer_field("scan_near_window_px", c.scan_near_window_px, {1, 63, "px", "Side of the square window (odd) around a stereo match in which scan_near_max_dense_valid counts the dense matcher's valid disparities and scan_near_uniqueness compares patches. Sized to hold several of the dense matcher's 7-pixel windows and enough texture for a patch to be told from a period of a repeated one; 11 px is what the eval-scan sweeps and the clutter runs were measured with (docs/results.md)."});
  v.require(c.dense_window_px % 2 == 1, "dense_window_px", "must be odd");
  v.require(c.scan_near_window_px % 2 == 1, "scan_near_window_px", "must be odd");
  v.require(c.min_disparity_px < c.max_disparity_px, "max_disparity_px", "must be larger than min_disparity_px");
  v.end_section();
}

}  // namespace stereoscout::core
