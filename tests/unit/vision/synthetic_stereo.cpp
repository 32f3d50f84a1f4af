#include "synthetic_stereo.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stereoscout::vision::test {
namespace {

double lattice_value(std::int64_t x, std::int64_t y, std::int64_t z, std::uint32_t seed) {
  std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^
                    static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4FULL ^
                    static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ULL ^ (static_cast<std::uint64_t>(seed) << 32U);
  h ^= h >> 33U;
  h *= 0xFF51AFD7ED558CCDULL;
  h ^= h >> 33U;
  h *= 0xC4CEB9FE1A85EC53ULL;
  h ^= h >> 33U;
  return static_cast<double>(h >> 11U) / static_cast<double>(1ULL << 53U);
}

double smooth(double t) { return t * t * (3.0 - 2.0 * t); }

double value_noise(const Eigen::Vector3d& p, std::uint32_t seed) {
  const double fx = std::floor(p.x());
  const double fy = std::floor(p.y());
  const double fz = std::floor(p.z());
  const auto ix = static_cast<std::int64_t>(fx);
  const auto iy = static_cast<std::int64_t>(fy);
  const auto iz = static_cast<std::int64_t>(fz);
  const double tx = smooth(p.x() - fx);
  const double ty = smooth(p.y() - fy);
  const double tz = smooth(p.z() - fz);
  double result = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const int cx = corner & 1;
    const int cy = (corner >> 1) & 1;
    const int cz = (corner >> 2) & 1;
    const double weight = (cx != 0 ? tx : 1.0 - tx) * (cy != 0 ? ty : 1.0 - ty) * (cz != 0 ? tz : 1.0 - tz);
    result += weight * lattice_value(ix + cx, iy + cy, iz + cz, seed);
  }
  return result;
}

// Ray parameter of the nearest hit of a box, or +inf.
double intersect_box(const Box& box, const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) {
  double near = 0.0;
  double far = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    if (std::fabs(direction[axis]) < 1e-12) {
      if (origin[axis] < box.min_corner[axis] || origin[axis] > box.max_corner[axis]) {
        return std::numeric_limits<double>::infinity();
      }
      continue;
    }
    double t0 = (box.min_corner[axis] - origin[axis]) / direction[axis];
    double t1 = (box.max_corner[axis] - origin[axis]) / direction[axis];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
    if (near > far) {
      return std::numeric_limits<double>::infinity();
    }
  }
  return near > 1e-9 ? near : std::numeric_limits<double>::infinity();
}

void render_camera(const Scene& scene, const StereoCalibration& calibration, const Eigen::Isometry3d& world_from_camera,
                   cv::Mat& image, cv::Mat& depth) {
  image.create(calibration.height_px, calibration.width_px, CV_8UC1);
  depth.create(calibration.height_px, calibration.width_px, CV_64FC1);
  const Eigen::Vector3d origin = world_from_camera.translation();
  for (int y = 0; y < calibration.height_px; ++y) {
    for (int x = 0; x < calibration.width_px; ++x) {
      const Eigen::Vector3d ray_optical((x - calibration.principal_x_px) / calibration.focal_px,
                                        (y - calibration.principal_y_px) / calibration.focal_px, 1.0);
      const Eigen::Vector3d direction = world_from_camera.linear() * ray_optical;
      double t = std::numeric_limits<double>::infinity();
      if (scene.has_floor && direction.z() < -1e-12) {
        t = -origin.z() / direction.z();
      }
      for (const Box& box : scene.boxes) {
        t = std::min(t, intersect_box(box, origin, direction));
      }
      if (std::isfinite(t)) {
        // t scales a ray whose optical z is 1, so t is the depth Z.
        depth.at<double>(y, x) = t;
        image.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(std::clamp(surface_texture(scene, origin + t * direction), 0.0, 255.0));
      } else {
        depth.at<double>(y, x) = 0.0;
        image.at<std::uint8_t>(y, x) = 128;
      }
    }
  }
}

}  // namespace

double surface_texture(const Scene& scene, const Eigen::Vector3d& point) {
  // Three octaves of value noise (features of about 4, 10 and 30 cm), stretched to contrast.
  const double fine = value_noise(point / 0.04, scene.texture_seed);
  const double medium = value_noise(point / 0.10, scene.texture_seed + 1);
  const double coarse = value_noise(point / 0.30, scene.texture_seed + 2);
  const double value = 0.25 * fine + 0.45 * medium + 0.30 * coarse;
  return 128.0 + (value - 0.5) * 420.0;
}

Rendering render(const Scene& scene, const StereoCalibration& calibration, const core::CameraMount& mount,
                 const core::Pose2& robot_pose, double pan_rad) {
  Rendering rendering;
  rendering.world_from_right_camera = robot_pose.to_isometry3() * core::robot_from_camera(mount, pan_rad);
  Eigen::Isometry3d world_from_left = rendering.world_from_right_camera;
  // The left camera sits a baseline to the left: x = -B in the right camera's optical frame.
  world_from_left.translation() = rendering.world_from_right_camera * Eigen::Vector3d(-calibration.baseline_m, 0.0, 0.0);
  render_camera(scene, calibration, rendering.world_from_right_camera, rendering.frame.right, rendering.right_depth);
  render_camera(scene, calibration, world_from_left, rendering.frame.left, rendering.left_depth);
  rendering.frame.pan_rad = pan_rad;
  return rendering;
}

Scene textured_room() {
  Scene scene;
  const double thickness = 0.1;
  // Walls of a 8 m x 6 m room around the origin, 2.5 m high.
  scene.boxes.push_back({{4.0, -3.0, 0.0}, {4.0 + thickness, 3.0, 2.5}});
  scene.boxes.push_back({{-4.0 - thickness, -3.0, 0.0}, {-4.0, 3.0, 2.5}});
  scene.boxes.push_back({{-4.0, 3.0, 0.0}, {4.0, 3.0 + thickness, 2.5}});
  scene.boxes.push_back({{-4.0, -3.0 - thickness, 0.0}, {4.0, -3.0, 2.5}});
  // Some furniture in view of a robot at the origin looking along +x.
  scene.boxes.push_back({{2.0, -1.2, 0.0}, {2.6, -0.4, 0.8}});
  scene.boxes.push_back({{2.8, 0.6, 0.0}, {3.3, 1.4, 1.5}});
  return scene;
}

}  // namespace stereoscout::vision::test
