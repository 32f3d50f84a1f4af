#pragma once
// The building's axes, for a heading observation from walls (filter.manhattan_heading_sigma_deg).
//
// Most indoor walls meet at right angles, so a wall's direction in the map frame, taken
// modulo 90 degrees, is one angle for the whole building. Walls seen from the start, while
// the estimate's heading is still near exact, learn it: the circular mean of four times
// their directions. When `walls_to_fix` walls agree (their resultant at least
// kMinAgreement) the axes are fixed and never learnt again; when they do not, learning
// starts over (counted). Once fixed, offset() says how far a wall's direction lies from the
// nearest axis, which a particle whose heading is right makes small.

#include <cstdint>

namespace stereoscout::slam {

class ManhattanFrame {
 public:
  // Resultant length, 0..1, at which the learnt walls are taken to share axes.
  static constexpr double kMinAgreement = 0.9;

  explicit ManhattanFrame(int walls_to_fix = 5) : walls_to_fix_(walls_to_fix < 1 ? 1 : walls_to_fix) {}

  void reset();
  // A wall at `map_direction_rad` (any multiple of pi apart is the same wall). Ignored once fixed.
  void learn(double map_direction_rad);

  bool fixed() const { return fixed_; }
  // The first axis, in [-pi/4, pi/4); the others are multiples of pi/2 from it.
  double axis_rad() const { return axis_rad_; }
  // The signed angle from the nearest axis to `map_direction_rad`, in [-pi/4, pi/4).
  double offset(double map_direction_rad) const;
  std::uint64_t restarts() const { return restarts_; }

 private:
  int walls_to_fix_;
  int learnt_ = 0;
  double sum_cos_ = 0.0;
  double sum_sin_ = 0.0;
  bool fixed_ = false;
  double axis_rad_ = 0.0;
  std::uint64_t restarts_ = 0;
};

}  // namespace stereoscout::slam
