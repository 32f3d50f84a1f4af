#include "rendered_scan.hpp"

#include "stereoscout/vision/calibration.hpp"

namespace stereoscout::cli {
namespace {

core::CameraMount mount_of(const core::CameraConfig& camera) {
  return {camera.mount_x_m, camera.mount_y_m, camera.mount_height_m, core::degrees_to_radians(camera.mount_tilt_deg)};
}

}  // namespace

RenderedScanner::RenderedScanner(const host_sim::World& world, const core::SystemConfig& config)
    : renderer_(world, config.camera, config.sim, static_cast<std::uint64_t>(config.run.seed)),
      front_end_(config.vision, config.robot, vision::calibration_from_config(config.camera), mount_of(config.camera)),
      near_matches_(config.vision.scan_near_min_matches > 0),
      observations_(near_matches_ ? front_end_.max_observations() : 0) {
  frame_.allocate(config.camera.width_px, config.camera.height_px);
  front_end_.allocate_scan(scan_);
}

bool RenderedScanner::scan_at(const core::Pose2& pose, std::uint32_t frame_index) {
  renderer_.render(pose, 0.0, 0.0, frame_index, frame_.left, frame_.right, nullptr);
  frame_.timestamp_ns = frame_index;
  if (near_matches_ && !front_end_.observe_landmarks(frame_, observations_).ok()) return false;
  return front_end_.scan(frame_, scan_).ok();
}

}  // namespace stereoscout::cli
