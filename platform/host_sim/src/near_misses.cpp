#include "stereoscout/host_sim/near_misses.hpp"

namespace stereoscout::host_sim {
namespace {
// An approach ends this far above the threshold, as a contact ends 2 cm clear (simulator.cpp).
constexpr double kHysteresis_m = 0.02;
}  // namespace

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
  if (clearance_m < threshold_m_ + kHysteresis_m) return;
  open_ = false;
  if (touched_) return;
  if (completed_ < kLogSize) log_[static_cast<std::size_t>(completed_)] = closest_;
  ++completed_;
}

void NearMisses::touched() {
  if (threshold_m_ <= 0.0) return;
  if (!open_) closest_ = Event{};
  open_ = true;
  touched_ = true;
}

}  // namespace stereoscout::host_sim
