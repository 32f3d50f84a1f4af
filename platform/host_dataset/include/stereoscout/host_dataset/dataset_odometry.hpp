#pragma once
// Wheel odometry for a dataset that has none (KITTI): the ground-truth motion between two
// frames on the ground plane, corrupted by the simulator's kind of noise (config `dataset`,
// same meaning as sim.tile): a random walk in distance and heading (variance proportional to
// distance driven and angle turned) and a systematic scale error and heading drift per metre.
// The noise of frame k comes from RandomStream(seed, {dataset_odometry, k, 0}), so a reading
// depends only on the seed and the frame, never on how often read() was called before.

#include <cstdint>
#include <vector>

#include "stereoscout/core/config/sim.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/random.hpp"
#include "stereoscout/platform/odometry.hpp"

namespace stereoscout::host_dataset {

// Noise: core::corrupt_motion (core/odometry_noise.hpp), the simulator's model.
class DatasetOdometry : public platform::Odometry {
 public:
  // One reading per frame: `truth[k]` is the true robot pose at `times_s[k]` (same length).
  // The odometry frame starts at truth[0].
  DatasetOdometry(std::vector<core::Pose2> truth, std::vector<double> times_s, const core::OdometryNoiseConfig& noise,
                  std::uint64_t seed);

  // The reading of the next frame; not_available after the last.
  core::Status read(core::OdometryReading& reading) override;

  std::size_t next_frame() const { return next_; }

 private:
  std::vector<core::Pose2> truth_;
  std::vector<double> times_s_;
  core::OdometryNoiseConfig noise_;
  std::uint64_t seed_;
  std::size_t next_ = 0;
  core::Pose2 pose_;
};

}  // namespace stereoscout::host_dataset
