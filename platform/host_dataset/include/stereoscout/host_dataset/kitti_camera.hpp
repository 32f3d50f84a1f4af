#pragma once
// A KITTI odometry folder played through the platform Camera interface: one rectified pair per
// grab(), in frame order, stamped with times.txt. image_0 is KITTI's left camera, image_1 the
// right. A pair that cannot be read (missing file, not an image, wrong size) is skipped and
// counted; its path is kept for the caller's message. Host tool: reading a PNG allocates.

#include <cstdint>
#include <string>

#include "stereoscout/host_dataset/kitti_sequence.hpp"
#include "stereoscout/platform/camera.hpp"

namespace stereoscout::host_dataset {

class KittiCamera : public platform::Camera {
 public:
  explicit KittiCamera(const KittiSequence& sequence) : sequence_(sequence) {}

  // ok: `frame` holds pair `next_frame() - 1`. io_error / invalid_input: that pair was
  // skipped (see last_failed_path()); the next call moves on. not_available: sequence over.
  core::Status grab(core::StereoFrame& frame) override;
  void command_pan(double /*pan_rad*/) override {}  // KITTI's cameras do not pan

  std::size_t next_frame() const { return next_; }
  bool finished() const { return next_ >= sequence_.frames(); }
  std::uint64_t pairs_delivered() const { return delivered_; }
  std::uint64_t pairs_skipped() const { return skipped_; }
  const std::string& last_failed_path() const { return last_failed_path_; }

 private:
  const KittiSequence& sequence_;
  std::size_t next_ = 0;
  std::uint64_t delivered_ = 0;
  std::uint64_t skipped_ = 0;
  std::string last_failed_path_;
};

}  // namespace stereoscout::host_dataset
