#include "stereoscout/host_sim/near_misses.hpp"

namespace stereoscout::host_sim {

void NearMisses::moved(double time_s, const core::Pose2& pose, double clearance_m) {
  if (threshold_m_ <= 0.0) return;
  if (!open_) {
    if (clearance_m >= threshold_m_) return;
    open_ = true;
    touched_ = false;
    closest_ = Event{time_s, pose, clearance_m};
    return;
  }
  if (clearance_m < closest_.clearance_m) closest_ = Event{time_s, pose, clearance_m};
  if (clearance_m < threshold_m_ + hysteresis_m_) return;
  open_ = false;
  if (touched_) return;
  if (completed_ < kLogSize) log_[static_cast<std::size_t>(completed_)] = closest_;
  ++completed_;
}

// A touched approach is never logged, so its closest point is left as it is.
void NearMisses::touched() {
  open_ = true;
  touched_ = true;
}

}  // namespace stereoscout::host_sim
