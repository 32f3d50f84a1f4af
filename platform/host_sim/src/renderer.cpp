// Column-wise 2.5D stereo renderer (see renderer.hpp for the method).
//
// Geometry of one column: with the optical axis at heading phi and x = (u - cx) / f, the ray
// direction in the floor plane is d = forward + x * right, left unnormalised so that the ray
// parameter t of a crossing IS the optical depth Z of every point of that crossing (paper
// eq. 3: Z = f B / d). Row r sees height h - (r - cy) Z / f at depth Z.
#include "stereoscout/host_sim/renderer.hpp"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>

#include "stereoscout/core/check.hpp"
#include "stereoscout/core/random.hpp"

namespace stereoscout::host_sim {
namespace {

constexpr double kNearClip_m = 0.01;
constexpr double kFloorRasterCell_m = 0.05;
constexpr std::size_t kNoiseTableSize = 1 << 16;

double cross(const Eigen::Vector2d& p, const Eigen::Vector2d& q) { return p.x() * q.y() - p.y() * q.x(); }

// Gray level of a texel on a surface under a light gain and the exposure (see Surface).
struct Shading {
  float scale;
  float offset;
  Shading(const Surface& surface, float gain, float exposure) {
    const float radiance = 255.0F * exposure * gain;
    scale = radiance * surface.contrast / 255.0F;
    offset = radiance * (surface.brightness - 0.5F * surface.contrast);
  }
  std::uint8_t operator()(std::uint8_t texel) const {
    const float value = scale * static_cast<float>(texel) + offset + 0.5F;
    return static_cast<std::uint8_t>(std::clamp(value, 0.0F, 255.0F));
  }
};

bool same_surface(const Surface& a, const Surface& b) {
  return a.texture == b.texture && a.brightness == b.brightness && a.contrast == b.contrast &&
         a.texture_offset_u_m == b.texture_offset_u_m && a.texture_offset_v_m == b.texture_offset_v_m;
}

}  // namespace

std::string check_camera_supported(const core::CameraConfig& camera) {
  if (camera.mount_tilt_deg != 0.0) {
    return "camera.mount_tilt_deg: the simulator renders only an untilted camera (0), whose image columns are "
           "vertical planes (paper's assumption); got " + core::format_number(camera.mount_tilt_deg);
  }
  return {};
}

StereoRenderer::StereoRenderer(const World& world, const core::CameraConfig& camera, const core::SimConfig& sim,
                               std::uint64_t noise_seed)
    : world_(world),
      camera_(camera),
      sim_(sim),
      noise_seed_(noise_seed),
      textures_(world),
      height_m_(camera.mount_height_m) {
  // Callers check the config with check_camera_supported() and report it; reaching here with
  // a tilted camera is a programming error.
  STEREOSCOUT_CHECK(check_camera_supported(camera).empty(), "StereoRenderer needs camera.mount_tilt_deg == 0");
  const auto width = static_cast<std::size_t>(camera.width_px);
  const auto height = static_cast<std::size_t>(camera.height_px);
  hits_.resize(static_cast<std::size_t>(sim.max_hits_per_column));
  row_done_.resize(height);
  std::size_t max_polygon = 4;
  for (const Prism& prism : world.prisms) max_polygon = std::max(max_polygon, prism.polygon.size());
  crossing_depth_.resize(max_polygon);
  crossing_u_.resize(max_polygon);
  people_positions_.resize(world.people.size());
  for (const Prism& prism : world.prisms) {
    Eigen::Vector2d center = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& p : prism.polygon) center += p;
    center /= static_cast<double>(prism.polygon.size());
    double radius = 0.0;
    for (const Eigen::Vector2d& p : prism.polygon) radius = std::max(radius, (p - center).norm());
    prism_bounds_.emplace_back(center.x(), center.y(), radius);
  }
  column_x_.resize(width);
  for (std::size_t u = 0; u < width; ++u) {
    column_x_[u] = (static_cast<double>(u) - camera.principal_x_px) / camera.focal_px;
  }
  // Floor raster: which floor region and which light gain at each 5 cm cell.
  raster_origin_ = world.bounds_min() - Eigen::Vector2d::Constant(1.0);
  const Eigen::Vector2d extent = world.bounds_max() + Eigen::Vector2d::Constant(1.0) - raster_origin_;
  raster_width_ = static_cast<int>(std::ceil(extent.x() / kFloorRasterCell_m));
  raster_height_ = static_cast<int>(std::ceil(extent.y() / kFloorRasterCell_m));
  raster_gain_.resize(static_cast<std::size_t>(raster_width_) * static_cast<std::size_t>(raster_height_));
  raster_look_.resize(raster_gain_.size());
  for (int iy = 0; iy < raster_height_; ++iy) {
    for (int ix = 0; ix < raster_width_; ++ix) {
      const Eigen::Vector2d point = raster_origin_ + kFloorRasterCell_m * Eigen::Vector2d(ix + 0.5, iy + 0.5);
      const Surface* surface = &world.floor;
      for (const FloorRegion& region : world.floor_regions) {
        if (polygon_contains(region.polygon, point)) surface = &region.surface;
      }
      const auto gain = static_cast<float>(world.light_gain_at(point));
      const std::size_t index = static_cast<std::size_t>(iy) * static_cast<std::size_t>(raster_width_) + static_cast<std::size_t>(ix);
      raster_gain_[index] = gain;
      std::size_t look = 0;
      while (look < floor_looks_.size() &&
             !(same_surface(floor_looks_[look].surface, *surface) && floor_looks_[look].gain == gain)) {
        ++look;
      }
      if (look == floor_looks_.size() && look < 255) {
        const Shading shading(*surface, gain, static_cast<float>(sim.exposure));
        floor_looks_.push_back({*surface, gain, shading.scale, shading.offset});
      }
      raster_look_[index] = static_cast<std::uint8_t>(std::min<std::size_t>(look, floor_looks_.size() - 1));
    }
  }
  // Per-row depth of the floor and the ceiling, and the mip level for the pixel's footprint
  // (seen at a slant, a pixel covers Z/f across and Z^2/(f h) along the ray; use their mean).
  floor_row_depth_.assign(height, 0.0F);
  ceiling_row_depth_.assign(height, 0.0F);
  floor_row_level_.assign(height, 0);
  ceiling_row_level_.assign(height, 0);
  for (std::size_t r = 0; r < height; ++r) {
    const double offset = static_cast<double>(r) - camera.principal_y_px;
    const double drop = offset > 0.0 ? height_m_ : height_m_ - world.ceiling_height;
    if (offset == 0.0 || drop * offset <= 0.0) continue;
    const double z_depth = camera.focal_px * drop / offset;
    const double footprint = z_depth / camera.focal_px * std::sqrt(std::max(1.0, z_depth / std::abs(drop)));
    const auto level = static_cast<std::uint8_t>(TextureBank::level_for_footprint(footprint));
    (offset > 0.0 ? floor_row_depth_ : ceiling_row_depth_)[r] = static_cast<float>(z_depth);
    (offset > 0.0 ? floor_row_level_ : ceiling_row_level_)[r] = level;
  }
  // Sensor noise: a table of Gaussian gray-level offsets read from a random start per row.
  noise_table_.resize(kNoiseTableSize + width);
  core::RandomStream random(noise_seed, {core::stream_purpose::sim_image_noise, 0xFFFFFFFFU, 0});
  for (std::int16_t& value : noise_table_) {
    value = static_cast<std::int16_t>(std::lround(std::clamp(random.gaussian(0.0, sim.image_noise_sigma), -255.0, 255.0)));
  }
  left_transposed_.create(camera.width_px, camera.height_px, CV_8UC1);
  right_transposed_.create(camera.width_px, camera.height_px, CV_8UC1);
  depth_transposed_.create(camera.width_px, camera.height_px, CV_32FC1);
}

StereoRenderer::CameraPlacement StereoRenderer::place_camera(const core::Pose2& robot_pose, double pan_rad) const {
  const core::CameraMount mount{camera_.mount_x_m, camera_.mount_y_m, camera_.mount_height_m, 0.0};
  const Eigen::Isometry3d robot_from_camera = core::robot_from_camera(mount, pan_rad);
  const Eigen::Vector3d right = robot_from_camera.translation();
  const Eigen::Vector3d left = robot_from_camera * Eigen::Vector3d(-camera_.baseline_m, 0.0, 0.0);
  return {robot_pose.transform_point(right.head<2>()), robot_pose.transform_point(left.head<2>()), right.z(),
          robot_pose.theta + pan_rad};
}

std::size_t StereoRenderer::raster_index(double x, double y) const {
  const int ix = std::clamp(static_cast<int>((x - raster_origin_.x()) * (1.0 / kFloorRasterCell_m)), 0, raster_width_ - 1);
  const int iy = std::clamp(static_cast<int>((y - raster_origin_.y()) * (1.0 / kFloorRasterCell_m)), 0, raster_height_ - 1);
  return static_cast<std::size_t>(iy) * static_cast<std::size_t>(raster_width_) + static_cast<std::size_t>(ix);
}

void StereoRenderer::push_hit(const Hit& hit) {
  if (hit_count_ == hits_.size()) {
    ++dropped_hits_;
    // Keep the nearest: replace the farthest kept hit if the new one is nearer.
    auto farthest = std::max_element(hits_.begin(), hits_.end(),
                                     [](const Hit& l, const Hit& r) { return l.depth_in < r.depth_in; });
    if (hit.depth_in < farthest->depth_in) *farthest = hit;
    return;
  }
  hits_[hit_count_++] = hit;
}

void StereoRenderer::collect_hits(const Eigen::Vector2d& center, const Eigen::Vector2d& direction) {
  hit_count_ = 0;
  const double direction_norm = direction.norm();
  auto gain_at = [&](double depth) {
    const Eigen::Vector2d point = center + depth * direction;
    return floor_gain_at(point.x(), point.y());
  };
  for (const WallPiece& wall : world_.walls) {
    const Eigen::Vector2d edge = wall.b - wall.a;
    const double denominator = cross(direction, edge);
    if (std::abs(denominator) < 1e-12) continue;
    const Eigen::Vector2d to_start = wall.a - center;
    const double t = cross(to_start, edge) / denominator;
    const double s = cross(to_start, direction) / denominator;
    if (t < kNearClip_m || s < 0.0 || s > 1.0) continue;
    push_hit({static_cast<float>(t), static_cast<float>(t), static_cast<float>(wall.z_min), static_cast<float>(wall.z_max),
              static_cast<float>(wall.texture_u0_m + s * edge.norm()), gain_at(t), false, &wall.surface});
  }
  for (std::size_t p = 0; p < world_.prisms.size(); ++p) {
    const Eigen::Vector3d& bound = prism_bounds_[p];
    const Eigen::Vector2d to_center = bound.head<2>() - center;
    if (std::abs(cross(direction, to_center)) > bound.z() * direction_norm ||
        to_center.dot(direction) < -bound.z() * direction_norm) {
      continue;
    }
    const Prism& prism = world_.prisms[p];
    std::size_t count = 0;
    double perimeter = 0.0;
    for (std::size_t i = 0; i < prism.polygon.size(); ++i) {
      const Eigen::Vector2d& a = prism.polygon[i];
      const Eigen::Vector2d edge = prism.polygon[(i + 1) % prism.polygon.size()] - a;
      const double length = edge.norm();
      const double denominator = cross(direction, edge);
      if (std::abs(denominator) > 1e-12) {
        const Eigen::Vector2d to_start = a - center;
        const double t = cross(to_start, edge) / denominator;
        const double s = cross(to_start, direction) / denominator;
        if (s >= 0.0 && s < 1.0) {
          if (t >= kNearClip_m) {
            // Insertion into the depth-sorted crossing list.
            std::size_t k = count++;
            for (; k > 0 && crossing_depth_[k - 1] > t; --k) {
              crossing_depth_[k] = crossing_depth_[k - 1];
              crossing_u_[k] = crossing_u_[k - 1];
            }
            crossing_depth_[k] = t;
            crossing_u_[k] = perimeter + s * length;
          }
        }
      }
      perimeter += length;
    }
    // An odd number of crossings ahead means the camera is inside the footprint.
    const bool inside = (count % 2) == 1;
    std::size_t k = 0;
    if (inside) {
      push_hit({static_cast<float>(kNearClip_m), static_cast<float>(crossing_depth_[0]), static_cast<float>(prism.z_min),
                static_cast<float>(prism.z_max), 0.0F, gain_at(kNearClip_m), true, &prism.surface});
      k = 1;
    }
    for (; k + 1 < count; k += 2) {
      push_hit({static_cast<float>(crossing_depth_[k]), static_cast<float>(crossing_depth_[k + 1]),
                static_cast<float>(prism.z_min), static_cast<float>(prism.z_max), static_cast<float>(crossing_u_[k]),
                gain_at(crossing_depth_[k]), true, &prism.surface});
    }
  }
  auto cylinder = [&](const Eigen::Vector2d& position, double radius, double z_min, double z_max, const Surface& surface) {
    const Eigen::Vector2d offset = center - position;
    const double a = direction.squaredNorm();
    const double b = 2.0 * direction.dot(offset);
    const double c = offset.squaredNorm() - radius * radius;
    const double discriminant = b * b - 4.0 * a * c;
    if (discriminant <= 0.0) return;
    const double root = std::sqrt(discriminant);
    const double t_out = (-b + root) / (2.0 * a);
    if (t_out < kNearClip_m) return;
    const double t_in = std::max((-b - root) / (2.0 * a), kNearClip_m);
    const Eigen::Vector2d hit = offset + t_in * direction;
    const double u = radius * (std::atan2(hit.y(), hit.x()) + core::kPi);
    push_hit({static_cast<float>(t_in), static_cast<float>(t_out), static_cast<float>(z_min), static_cast<float>(z_max),
              static_cast<float>(u), gain_at(t_in), true, &surface});
  };
  for (const Cylinder& c : world_.cylinders) cylinder(c.center, c.radius, c.z_min, c.z_max, c.surface);
  for (std::size_t i = 0; i < world_.people.size(); ++i) {
    const Person& person = world_.people[i];
    cylinder(people_positions_[i], person.radius, 0.0, person.height, person.surface);
  }
  std::sort(hits_.begin(), hits_.begin() + static_cast<std::ptrdiff_t>(hit_count_),
            [](const Hit& l, const Hit& r) { return l.depth_in < r.depth_in; });
}

void StereoRenderer::fill_vertical(const Hit& hit, std::uint8_t* pixels, float* depth) {
  const double f = camera_.focal_px;
  const double cy = camera_.principal_y_px;
  const double z_depth = hit.depth_in;
  const int last_row = camera_.height_px - 1;
  const int r0 = std::max(0, static_cast<int>(std::ceil(cy + f * (height_m_ - hit.z_max) / z_depth)));
  const int r1 = std::min(last_row, static_cast<int>(std::floor(cy + f * (height_m_ - hit.z_min) / z_depth)));
  if (r1 < r0) return;
  const Surface& surface = *hit.surface;
  const int level_index = TextureBank::level_for_footprint(z_depth / f);
  const TextureBank::Level& level = textures_.level(surface.texture, level_index);
  const int iu = TextureBank::texel_coordinate(level_index, hit.texture_u_m + surface.texture_offset_u_m);
  const Shading shading(surface, hit.gain, static_cast<float>(sim_.exposure));
  const double v_per_row = -z_depth / f;  // height change per image row
  const double v_start = height_m_ - (r0 - cy) * z_depth / f + surface.texture_offset_v_m + 4096.0;
  const auto depth_value = static_cast<float>(z_depth);
  for (int r = r0; r <= r1; ++r) {
    if (row_done_[static_cast<std::size_t>(r)] != 0) continue;
    const int iv = static_cast<int>((v_start + (r - r0) * v_per_row) * level.texels_per_m);
    pixels[r] = shading(textures_.texel(surface.texture, level_index, iu, iv));
    depth[r] = depth_value;
    row_done_[static_cast<std::size_t>(r)] = 1;
  }
}

void StereoRenderer::fill_horizontal(float plane_z, float from_depth, float to_depth, const Surface& surface, float gain,
                                     const Eigen::Vector2d& center, const Eigen::Vector2d& direction,
                                     std::uint8_t* pixels, float* depth) {
  const double f = camera_.focal_px;
  const double cy = camera_.principal_y_px;
  const double drop = height_m_ - plane_z;  // > 0: plane below the camera, seen below the horizon
  if (std::abs(drop) < 1e-9) return;
  const double row_a = cy + f * drop / from_depth;
  const double row_b = cy + f * drop / to_depth;
  int r0 = static_cast<int>(std::ceil(std::min(row_a, row_b)));
  int r1 = static_cast<int>(std::floor(std::max(row_a, row_b)));
  r0 = std::max(r0, 0);
  r1 = std::min(r1, camera_.height_px - 1);
  const Shading shading(surface, gain, static_cast<float>(sim_.exposure));
  for (int r = r0; r <= r1; ++r) {
    const double offset = r - cy;
    if (row_done_[static_cast<std::size_t>(r)] != 0 || offset * drop <= 0.0) continue;
    const double z_depth = f * drop / offset;
    const Eigen::Vector2d point = center + z_depth * direction;
    // Seen at a slant, a pixel covers Z/f across and Z^2/(f h) along the ray; use their mean.
    const double footprint = z_depth / f * std::sqrt(std::max(1.0, z_depth / std::abs(drop)));
    const std::uint8_t texel = textures_.sample(surface.texture, TextureBank::level_for_footprint(footprint),
                                                point.x() + surface.texture_offset_u_m, point.y() + surface.texture_offset_v_m);
    pixels[r] = shading(texel);
    depth[r] = static_cast<float>(z_depth);
    row_done_[static_cast<std::size_t>(r)] = 1;
  }
}

void StereoRenderer::shade_column(const Eigen::Vector2d& center, const Eigen::Vector2d& direction, std::uint8_t* pixels,
                                  float* depth) {
  std::fill(row_done_.begin(), row_done_.end(), std::uint8_t{0});
  const auto ceiling = static_cast<float>(world_.ceiling_height);
  for (std::size_t i = 0; i < hit_count_; ++i) {
    const Hit& hit = hits_[i];
    fill_vertical(hit, pixels, depth);
    if (hit.solid && hit.z_max < height_m_) {
      fill_horizontal(hit.z_max, hit.depth_in, hit.depth_out, *hit.surface, hit.gain, center, direction, pixels, depth);
    }
    if (hit.solid && hit.z_min > height_m_) {
      fill_horizontal(hit.z_min, hit.depth_in, hit.depth_out, *hit.surface, hit.gain, center, direction, pixels, depth);
    }
    // A floor-to-ceiling surface hides everything behind it.
    if (hit.z_min <= 0.0F && hit.z_max >= ceiling) break;
  }
  fill_floor_and_ceiling(center, direction, pixels, depth);
}

void StereoRenderer::fill_floor_and_ceiling(const Eigen::Vector2d& center, const Eigen::Vector2d& direction,
                                            std::uint8_t* pixels, float* depth) {
  const Surface& ceiling = world_.ceiling;
  const Shading ceiling_shading(ceiling, 1.0F, static_cast<float>(sim_.exposure));
  for (std::size_t r = 0; r < row_done_.size(); ++r) {
    if (row_done_[r] != 0) continue;
    const float floor_depth = floor_row_depth_[r];
    if (floor_depth > 0.0F) {
      const Eigen::Vector2d point = center + static_cast<double>(floor_depth) * direction;
      const FloorLook& look = floor_looks_[raster_look_[raster_index(point.x(), point.y())]];
      const std::uint8_t texel = textures_.sample(look.surface.texture, floor_row_level_[r],
                                                  point.x() + look.surface.texture_offset_u_m,
                                                  point.y() + look.surface.texture_offset_v_m);
      const float value = look.scale * static_cast<float>(texel) + look.offset + 0.5F;
      pixels[r] = static_cast<std::uint8_t>(std::clamp(value, 0.0F, 255.0F));
      depth[r] = floor_depth;
    } else if (ceiling_row_depth_[r] > 0.0F) {
      const Eigen::Vector2d point = center + static_cast<double>(ceiling_row_depth_[r]) * direction;
      pixels[r] = ceiling_shading(textures_.sample(ceiling.texture, ceiling_row_level_[r],
                                                   point.x() + ceiling.texture_offset_u_m,
                                                   point.y() + ceiling.texture_offset_v_m));
      depth[r] = ceiling_row_depth_[r];
    } else {  // exactly on the horizon: nothing there
      pixels[r] = 0;
      depth[r] = 0.0F;
    }
  }
}

void StereoRenderer::render_view(const Eigen::Vector2d& center, double heading, cv::Mat& image_transposed,
                                 cv::Mat* depth_transposed) {
  const Eigen::Vector2d forward(std::cos(heading), std::sin(heading));
  const Eigen::Vector2d right(std::sin(heading), -std::cos(heading));
  cv::Mat& depth = depth_transposed != nullptr ? *depth_transposed : depth_transposed_;
  for (int u = 0; u < camera_.width_px; ++u) {
    const Eigen::Vector2d direction = forward + column_x_[static_cast<std::size_t>(u)] * right;
    collect_hits(center, direction);
    shade_column(center, direction, image_transposed.ptr<std::uint8_t>(u), depth.ptr<float>(u));
  }
}

void StereoRenderer::add_noise(cv::Mat& image, std::uint32_t frame_index, std::uint32_t camera_index) {
  if (sim_.image_noise_sigma <= 0.0) return;
  core::RandomStream random(noise_seed_, {core::stream_purpose::sim_image_noise, frame_index, camera_index});
  for (int r = 0; r < image.rows; ++r) {
    const std::int16_t* noise = noise_table_.data() + random.uniform_index(static_cast<std::uint32_t>(kNoiseTableSize));
    std::uint8_t* row = image.ptr<std::uint8_t>(r);
    for (int c = 0; c < image.cols; ++c) {
      // A saturated pixel stays saturated: the sensor clips after its noise.
      if (row[c] != 255) row[c] = static_cast<std::uint8_t>(std::clamp(row[c] + noise[c], 0, 255));
    }
  }
}

void StereoRenderer::render(const core::Pose2& robot_pose, double pan_rad, double time_s, std::uint32_t frame_index,
                            cv::Mat& left, cv::Mat& right, cv::Mat* depth_right) {
  for (std::size_t i = 0; i < people_positions_.size(); ++i) people_positions_[i] = world_.person_position(i, time_s);
  const CameraPlacement placement = place_camera(robot_pose, pan_rad);
  height_m_ = placement.height_m;
  render_view(placement.right_center, placement.heading_rad, right_transposed_, &depth_transposed_);
  cv::transpose(right_transposed_, right);
  if (depth_right != nullptr) cv::transpose(depth_transposed_, *depth_right);
  render_view(placement.left_center, placement.heading_rad, left_transposed_, nullptr);
  cv::transpose(left_transposed_, left);
  add_noise(left, frame_index, 0);
  add_noise(right, frame_index, 1);
}

}  // namespace stereoscout::host_sim
