#pragma once
// The 2.5D scan of a world's rendered view at a true pose: the simulator's renderer and the
// real vision front end, no filter. For scoring the scan (eval-scan) and the grid it builds
// (the corridor test) apart from localisation.

#include <cstdint>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/core/system_config.hpp"
#include "stereoscout/host_sim/renderer.hpp"
#include "stereoscout/host_sim/world.hpp"
#include "stereoscout/vision/front_end.hpp"

namespace stereoscout::cli {

class RenderedScanner {
 public:
  // The camera must be one the renderer supports (host_sim::check_camera_supported);
  // `world` is held by reference and must outlive the scanner.
  RenderedScanner(const host_sim::World& world, const core::SystemConfig& config);

  // Renders the view at `pose` (pan 0; `frame_index` seeds its noise and stamps the pair) and
  // scans it, with the SIFT stereo matches first when vision.scan_near_min_matches asks for
  // them (near surfaces); false when the front end rejects the pair. The scan is valid until
  // the next call.
  bool scan_at(const core::Pose2& pose, std::uint32_t frame_index);
  const core::DepthScan& scan() const { return scan_; }

 private:
  host_sim::StereoRenderer renderer_;
  vision::VisionFrontEnd front_end_;
  core::StereoFrame frame_;
  core::DepthScan scan_;
  bool near_matches_;
  core::FixedVector<core::LandmarkObservation> observations_;
};

}  // namespace stereoscout::cli
