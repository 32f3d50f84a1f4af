#pragma once
// Config section `explore`: frontier-value goal selection, planning, driving (paper VI).
#include "stereoscout/core/config.hpp"

namespace stereoscout::core {

struct ExploreConfig {
  double ray_step_deg = 5.0;
  double preferred_distance_m = 2.0;
  double distance_sigma_m = 0.5;
  double safety_margin_m = 0.10;
  double min_goal_value = 0.5;
  double goal_tolerance_m = 0.25;
  int goal_failures_before_blacklist = 3;
  bool pan_at_goal = true;
  bool return_to_start = true;
};

inline void describe(ConfigVisitor& v, ExploreConfig& c) {
  v.begin_section("explore", "Exploration: goal value H(s), A* planning and path following (paper VI).");
  v.number("ray_step_deg", c.ray_step_deg, {0.5, 90.0, "deg", "Angle between the rays cast from a candidate goal (paper 5)."});
  v.number("preferred_distance_m", c.preferred_distance_m, {0.1, 20.0, "m", "r*: distance to unknown space that maximises V (paper 2.0)."});
  v.number("distance_sigma_m", c.distance_sigma_m, {0.01, 10.0, "m", "sigma of V (paper 0.5)."});
  v.number("safety_margin_m", c.safety_margin_m, {0.0, 2.0, "m", "Added to the robot radius when inflating obstacles."});
  v.number("min_goal_value", c.min_goal_value, {0.0, 1000.0, "", "Exploration ends when no goal is worth more than this."});
  v.number("goal_tolerance_m", c.goal_tolerance_m, {0.01, 5.0, "m", "A goal is reached within this distance."});
  v.integer_field("goal_failures_before_blacklist", c.goal_failures_before_blacklist, {1, 100, "", "A goal that failed this many times is never chosen again."});
  v.boolean("pan_at_goal", c.pan_at_goal, "Look around 360 degrees on reaching each goal (paper VI).");
  v.boolean("return_to_start", c.return_to_start, "Drive back to the start pose when exploration ends.");
  v.end_section();
}

}  // namespace stereoscout::core
