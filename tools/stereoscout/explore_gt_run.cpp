#include "explore_gt_run.hpp"
#include "reachable_coverage.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "stereoscout/host_sim/ground_truth.hpp"
#include "stereoscout/host_sim/renderer.hpp"
#include "stereoscout/host_sim/simulator.hpp"
#include "stereoscout/occupancy/occupancy_grid.hpp"
#include "stereoscout/occupancy/ros_map.hpp"
#include "stereoscout/stack/stack.hpp"
#include "stereoscout/vision/calibration.hpp"
#include "stereoscout/vision/obstacle_scan.hpp"

namespace stereoscout::cli {
namespace {

// Forward-maps the right image's ground-truth depth to a disparity map referenced to the left
// image, as the dense matcher would produce it: the nearest surface wins where two land on one
// pixel, and there is no disparity above the matcher's largest nor in its unmatched right
// border (ObstacleScanParams), so the scan sees what the stack's does.
void disparity_from_depth(const cv::Mat& depth_right, double focal_baseline, const vision::ObstacleScanParams& limits,
                          cv::Mat& disparity_left) {
  const int last_matched_left = depth_right.cols - 1 - limits.unmatched_border_px;
  disparity_left.setTo(0.0F);
  for (int y = 0; y < depth_right.rows; ++y) {
    const float* depth = depth_right.ptr<float>(y);
    float* disparity = disparity_left.ptr<float>(y);
    for (int x = 0; x < depth_right.cols; ++x) {
      if (!(depth[x] > 0.0F) || !std::isfinite(depth[x])) continue;
      const double d = focal_baseline / static_cast<double>(depth[x]);
      const long column = std::lround(x + d);
      if (column > last_matched_left || d > limits.max_disparity_px) continue;
      // The scanner recovers the right-image column as column - d (within half a pixel of x).
      float& out = disparity[column];
      const auto value = static_cast<float>(d);
      if (value > out) out = value;
    }
  }
}

// The final grid as a ROS map: <stem>.pgm and <stem>.yaml.
std::string write_grid(const occupancy::OccupancyGrid& grid, const occupancy::CellThresholds& thresholds,
                       const std::string& pgm_path) {
  const std::size_t dot = pgm_path.rfind('.');
  const std::string stem = dot == std::string::npos ? pgm_path : pgm_path.substr(0, dot);
  return occupancy::write_ros_map(occupancy::classify_grid(grid, thresholds), pgm_path, stem + ".yaml");
}

}  // namespace

ExploreGtResult run_explore_gt(const core::SystemConfig& config, const host_sim::World& world,
                               const ExploreGtOptions& options) {
  ExploreGtResult result;
  const std::string unsupported = host_sim::check_camera_supported(config.camera);
  if (!unsupported.empty()) {
    result.error = unsupported;
    return result;
  }
  const auto seed = static_cast<std::uint64_t>(config.run.seed);
  host_sim::Simulator simulator(world, config.robot, config.camera, config.sim, seed);
  simulator.teleport(world.start);
  host_sim::StereoRenderer renderer(world, config.camera, config.sim, seed);
  const core::CameraMount mount{config.camera.mount_x_m, config.camera.mount_y_m, config.camera.mount_height_m,
                                core::degrees_to_radians(config.camera.mount_tilt_deg)};
  const vision::ObstacleScanParams scan_params = vision::scan_params_from_config(config.vision, config.robot);
  vision::ObstacleScanner scanner(scan_params, vision::calibration_from_config(config.camera), mount);
  core::DepthScan scan;
  scanner.allocate(scan);
  std::vector<Eigen::Vector2d> seen_points(static_cast<std::size_t>(config.camera.width_px));
  explore::SeenObstacles seen;
  seen.points = seen_points.data();
  cv::Mat left(config.camera.height_px, config.camera.width_px, CV_8UC1);
  cv::Mat right(config.camera.height_px, config.camera.width_px, CV_8UC1);
  cv::Mat depth(config.camera.height_px, config.camera.width_px, CV_32FC1);
  cv::Mat disparity(config.camera.height_px, config.camera.width_px, CV_32FC1);
  const double focal_baseline = config.camera.focal_px * config.camera.baseline_m;

  const occupancy::GridGeometry geometry = occupancy::GridGeometry::centred_on(config.grid, world.start);
  occupancy::OccupancyGrid grid(geometry, occupancy::LogOddsModel::from_config(config.grid));
  const occupancy::CellThresholds thresholds = occupancy::CellThresholds::from_config(config.grid);
  std::vector<occupancy::CellState> cells(geometry.cell_count(), occupancy::CellState::unknown);
  std::vector<std::uint8_t> in_view(cells.size(), 0);
  std::vector<std::uint8_t> looked_over(config.grid.looked_over_range_m > 0.0 ? cells.size() : 0, 0);
  std::uint8_t* const looked_over_marks = looked_over.empty() ? nullptr : looked_over.data();
  const explore::GridView view = stack::navigation_view(geometry, cells.data(), in_view.data(), looked_over_marks);

  core::ExploreConfig explore_config = config.explore;
  explore_config.time_limit_s = std::min(explore_config.time_limit_s, config.run.max_time_s);
  explore::Explorer explorer(explore::ExploreParams::from_config(explore_config, config.robot, config.camera, config.vision,
                                                                 geometry.width_cells, geometry.height_cells));
  const ReachableCoverage truth(config, world);
  result.reachable_cells = truth.reachable_cells();

  const double min_translation = config.robot.update_min_translation_m;
  const double min_rotation = core::degrees_to_radians(config.robot.update_min_rotation_deg);
  const double hard_limit_s = explore_config.time_limit_s + options.return_allowance_s;
  bool first = true;
  core::Pose2 last_update_pose;
  double last_update_camera_heading = 0.0;
  double next_sample_s = 0.0;
  std::uint32_t frame = 0;
  bool exploration_over = false;
  while (simulator.time_s() < hard_limit_s) {
    const core::Pose2 pose = simulator.true_pose();
    const double camera_heading = pose.theta + simulator.pan_rad();
    const bool update_due = first || (pose.translation() - last_update_pose.translation()).norm() > min_translation ||
                            std::abs(core::wrap_angle(camera_heading - last_update_camera_heading)) > min_rotation;
    if (update_due) {
      renderer.render(pose, simulator.pan_rad(), simulator.time_s(), frame++, left, right, &depth);
      disparity_from_depth(depth, focal_baseline, scan_params, disparity);
      scanner.compute(disparity, simulator.pan_rad(), simulator.time_ns(), scan);
      grid.insert(scan, pose);
      seen.count = explore::seen_obstacles_from_scan(scan, pose, seen_points.data(), seen_points.size());
      seen.time_s = simulator.time_s();
      seen.scan = &scan;
      seen.odometry = pose;  // ground truth here stands for odometry too
      seen.pose = pose;
      seen.pan_rad = simulator.pan_rad();
      occupancy::classify_cells(grid, thresholds, cells.data(), in_view.data(), looked_over_marks);
      last_update_pose = pose;
      last_update_camera_heading = camera_heading;
      first = false;
      ++result.updates;
    }
    if (simulator.time_s() >= next_sample_s) {
      result.coverage_curve.push_back(
          {simulator.time_s(), truth.coverage(view)});
      next_sample_s += options.coverage_sample_period_s;
    }
    explore::ExploreInput input;
    input.time_s = simulator.time_s();
    input.pose = pose;
    input.odometry = pose;
    input.pan_rad = simulator.pan_rad();
    input.grid = view;
    input.seen = seen;
    input.grid_updated = update_due;
    const explore::ExploreOutput output = explorer.step(input);
    if (!exploration_over && explorer.finish_reason() != explore::FinishReason::none) {
      exploration_over = true;
      result.exploration_time_s = simulator.time_s();
    }
    if (output.state == explore::ExploreState::finished) break;
    simulator.command(output.drive);
    simulator.command_pan(output.pan_target_rad);
    const std::uint64_t collisions_before = simulator.collision_count();
    simulator.step(options.control_period_s);
    if (simulator.collision_count() > collisions_before && result.collision_log.size() < 8) {
      char line[200];
      std::snprintf(line, sizeof(line), "t=%.1f pose=(%.2f, %.2f, %.0f deg) v=%.3f w=%.3f state=%s", simulator.time_s(),
                    pose.x, pose.y, core::radians_to_degrees(pose.theta), output.drive.linear_mps,
                    output.drive.angular_rad_s, explore::to_string(output.state));
      result.collision_log.emplace_back(line);
    }
  }
  if (!exploration_over) result.exploration_time_s = simulator.time_s();
  result.total_time_s = simulator.time_s();
  result.covered_cells = truth.covered_cells(view);
  result.coverage = truth.coverage(view);
  result.coverage_curve.push_back({simulator.time_s(), result.coverage});
  result.collisions = simulator.collision_count();
  result.person_contacts = simulator.person_contact_count();
  result.distance_m = simulator.distance_travelled_m();
  result.distance_from_start_m = (simulator.true_pose().translation() - world.start.translation()).norm();
  result.counters = explorer.counters();
  result.finish_reason = explorer.finish_reason();
  result.final_state = explorer.state();
  if (!options.map_pgm.empty()) result.error = write_grid(grid, thresholds, options.map_pgm);
  return result;
}

std::string explore_gt_json(const std::string& world_name, const ExploreGtResult& result) {
  const explore::ExploreCounters& c = result.counters;
  const char* reason = result.finish_reason == explore::FinishReason::explored     ? "explored"
                       : result.finish_reason == explore::FinishReason::time_limit ? "time_limit"
                                                                                   : "none";
  // First sampled time at which the coverage reached 90% / 95% (-1: never).
  double time_to[2] = {-1.0, -1.0};
  const double levels[2] = {0.90, 0.95};
  for (int k = 0; k < 2; ++k) {
    for (const CoverageSample& sample : result.coverage_curve) {
      if (sample.coverage >= levels[k]) {
        time_to[k] = sample.time_s;
        break;
      }
    }
  }
  char buffer[2048];
  std::snprintf(buffer, sizeof(buffer),
                "{\"world\": \"%s\", \"coverage\": %.4f, \"time_to_90_s\": %.0f, \"time_to_95_s\": %.0f, \"reachable_cells\": %zu, \"covered_cells\": %zu, "
                "\"collisions\": %llu, \"person_contacts\": %llu, \"exploration_time_s\": %.1f, \"total_time_s\": %.1f, \"distance_m\": %.2f, "
                "\"distance_from_start_m\": %.2f, \"finish\": \"%s\", \"final_state\": \"%s\", \"updates\": %llu, "
                "\"goals_chosen\": %llu, \"goals_reached\": %llu, \"goals_abandoned\": %llu, \"goal_failures\": %llu, "
                "\"goals_blacklisted\": %llu, \"plan_failures\": %llu, \"replans\": %llu, \"stuck\": %llu, "
                "\"safety_stops\": %llu, \"stalls\": %llu, \"looks\": %llu, \"looks_before_giving_up\": %llu, \"return_failures\": %llu, \"contact_clears\": %llu}",
                world_name.c_str(), result.coverage, time_to[0], time_to[1], result.reachable_cells, result.covered_cells,
                static_cast<unsigned long long>(result.collisions),
                static_cast<unsigned long long>(result.person_contacts), result.exploration_time_s, result.total_time_s,
                result.distance_m, result.distance_from_start_m, reason, explore::to_string(result.final_state),
                static_cast<unsigned long long>(result.updates), static_cast<unsigned long long>(c.goals_chosen),
                static_cast<unsigned long long>(c.goals_reached), static_cast<unsigned long long>(c.goals_abandoned),
                static_cast<unsigned long long>(c.goal_failures), static_cast<unsigned long long>(c.goals_blacklisted),
                static_cast<unsigned long long>(c.plan_failures), static_cast<unsigned long long>(c.replans),
                static_cast<unsigned long long>(c.stuck), static_cast<unsigned long long>(c.safety_stops),
                static_cast<unsigned long long>(c.stalls),
                static_cast<unsigned long long>(c.looks), static_cast<unsigned long long>(c.looks_before_giving_up),
                static_cast<unsigned long long>(c.return_failures), static_cast<unsigned long long>(c.contact_clears));
  return buffer;
}

}  // namespace stereoscout::cli
