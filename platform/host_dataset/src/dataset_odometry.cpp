#include "stereoscout/host_dataset/dataset_odometry.hpp"

#include <cmath>
#include <utility>

#include "stereoscout/core/check.hpp"
#include "stereoscout/core/odometry_noise.hpp"

namespace stereoscout::host_dataset {

DatasetOdometry::DatasetOdometry(std::vector<core::Pose2> truth, std::vector<double> times_s,
                                 const core::OdometryNoiseConfig& noise, std::uint64_t seed)
    : truth_(std::move(truth)), times_s_(std::move(times_s)), noise_(noise), seed_(seed) {
  STEREOSCOUT_CHECK(truth_.size() == times_s_.size(), "one true pose per frame time");
  if (!truth_.empty()) pose_ = truth_.front();
}

core::Status DatasetOdometry::read(core::OdometryReading& reading) {
  if (next_ >= truth_.size()) return {core::StatusCode::not_available, "dataset odometry finished"};
  const std::size_t frame = next_++;
  if (frame > 0) {
    const core::Pose2 delta = truth_[frame - 1].between(truth_[frame]);
    core::RandomStream random(seed_, {core::stream_purpose::dataset_odometry, static_cast<std::uint32_t>(frame), 0});
    pose_ = pose_.compose(core::corrupt_motion(delta, noise_, random));
  }
  reading.timestamp_ns = static_cast<std::int64_t>(std::llround(times_s_[frame] * 1e9));
  reading.sequence = frame;
  reading.pose = pose_;
  return core::Status::success();
}

}  // namespace stereoscout::host_dataset
