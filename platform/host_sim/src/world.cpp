#include "stereoscout/host_sim/world.hpp"

#include <cmath>
#include <limits>

namespace stereoscout::host_sim {

bool polygon_contains(const std::vector<Eigen::Vector2d>& polygon, const Eigen::Vector2d& point) {
  bool inside = false;
  const std::size_t count = polygon.size();
  for (std::size_t i = 0, j = count - 1; i < count; j = i++) {
    const Eigen::Vector2d& a = polygon[i];
    const Eigen::Vector2d& b = polygon[j];
    if ((a.y() > point.y()) != (b.y() > point.y()) &&
        point.x() < (b.x() - a.x()) * (point.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

namespace {

template <class Visit>
void visit_static_points(const World& world, Visit visit) {
  for (const WallPiece& wall : world.walls) {
    visit(wall.a);
    visit(wall.b);
  }
  for (const Prism& prism : world.prisms) {
    for (const Eigen::Vector2d& p : prism.polygon) visit(p);
  }
  for (const Cylinder& cylinder : world.cylinders) {
    visit(cylinder.center - Eigen::Vector2d::Constant(cylinder.radius));
    visit(cylinder.center + Eigen::Vector2d::Constant(cylinder.radius));
  }
}

}  // namespace

Eigen::Vector2d World::bounds_min() const {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  visit_static_points(*this, [&](const Eigen::Vector2d& p) { low = low.cwiseMin(p); });
  return low;
}

Eigen::Vector2d World::bounds_max() const {
  Eigen::Vector2d high = Eigen::Vector2d::Constant(-std::numeric_limits<double>::infinity());
  visit_static_points(*this, [&](const Eigen::Vector2d& p) { high = high.cwiseMax(p); });
  return high;
}

FloorType World::floor_type_at(const Eigen::Vector2d& point) const {
  FloorType type = floor_type;
  for (const FloorRegion& region : floor_regions) {
    if (polygon_contains(region.polygon, point)) type = region.type;
  }
  return type;
}

double World::light_gain_at(const Eigen::Vector2d& point) const {
  double gain = 1.0;
  for (const LightRegion& light : lights) {
    if (polygon_contains(light.polygon, point)) gain = light.gain;
  }
  return gain;
}

Eigen::Vector2d World::person_position(std::size_t index, double time_s) const {
  const Person& person = people[index];
  const std::size_t count = person.waypoints.size();
  if (count < 2 || person.speed_mps <= 0.0) return person.waypoints.front();
  double loop_length = 0.0;
  for (std::size_t i = 0; i < count; ++i) loop_length += (person.waypoints[(i + 1) % count] - person.waypoints[i]).norm();
  if (loop_length <= 0.0) return person.waypoints.front();
  double travelled = std::fmod(person.speed_mps * time_s, loop_length);
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector2d& a = person.waypoints[i];
    const Eigen::Vector2d& b = person.waypoints[(i + 1) % count];
    const double length = (b - a).norm();
    if (travelled <= length && length > 0.0) return a + (b - a) * (travelled / length);
    travelled -= length;
  }
  return person.waypoints.front();
}

}  // namespace stereoscout::host_sim
