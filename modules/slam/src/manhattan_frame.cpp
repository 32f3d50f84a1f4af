#include "stereoscout/slam/manhattan_frame.hpp"

#include <cmath>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::slam {
namespace {

constexpr double kQuarterTurn = 0.5 * core::kPi;

}  // namespace

void ManhattanFrame::reset() {
  learnt_ = 0;
  sum_cos_ = 0.0;
  sum_sin_ = 0.0;
  fixed_ = false;
  axis_rad_ = 0.0;
  restarts_ = 0;
}

void ManhattanFrame::learn(double map_direction_rad) {
  if (fixed_) return;
  // Four times the direction: walls 90 degrees apart (and a wall's two senses) fall together.
  sum_cos_ += std::cos(4.0 * map_direction_rad);
  sum_sin_ += std::sin(4.0 * map_direction_rad);
  if (++learnt_ < walls_to_fix_) return;
  const double agreement = std::hypot(sum_cos_, sum_sin_) / static_cast<double>(learnt_);
  if (agreement >= kMinAgreement) {
    fixed_ = true;
    axis_rad_ = core::wrap_centred(0.25 * std::atan2(sum_sin_, sum_cos_), kQuarterTurn);
    return;
  }
  ++restarts_;
  learnt_ = 0;
  sum_cos_ = 0.0;
  sum_sin_ = 0.0;
}

double ManhattanFrame::offset(double map_direction_rad) const {
  return core::wrap_centred(map_direction_rad - axis_rad_, kQuarterTurn);
}

}  // namespace stereoscout::slam
