#pragma once
// Stereo renderer for the 2.5D world. Because every object is a vertical extrusion and the
// camera's image columns are perpendicular to the floor (tilt 0, as the paper assumes), each
// image column is one vertical plane: the renderer casts one 2D ray per column in the floor
// plane, collects the crossings with walls, prisms and cylinders sorted near to far, and fills
// the column's rows front to back; top faces (seen from above), bottom faces (seen from
// below), the floor and the ceiling are filled analytically. Cost: O(columns x primitives +
// pixels), a few milliseconds for a 640x480 pair.
//
// The right image is the reference of the stereo equations (paper eq. 3); the left camera
// sits `baseline` to its left, so a point at depth Z appears at u_left = u_right + f B / Z.

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "stereoscout/core/config/camera.hpp"
#include "stereoscout/core/config/sim.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/host_sim/textures.hpp"
#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::host_sim {

// Empty when the renderer supports `camera`; otherwise why not, naming the key.
// Only camera.mount_tilt_deg == 0 is supported (columns must stay vertical planes).
std::string check_camera_supported(const core::CameraConfig& camera);

class StereoRenderer {
 public:
  // Allocates everything (textures, floor raster, per-column buffers). `world` must outlive
  // the renderer. `noise_seed` keys the sensor noise (run.seed).
  StereoRenderer(const World& world, const core::CameraConfig& camera, const core::SimConfig& sim,
                 std::uint64_t noise_seed);

  // Renders the pair seen by the camera on a robot at `robot_pose` (world frame) with the pan
  // unit at `pan_rad`, people placed at simulated time `time_s`. `frame_index` keys the image
  // noise. `left`/`right` must be CV_8UC1 of the camera size (allocated by the caller once);
  // `depth_right`, if given, must be CV_32FC1 of that size and receives the ground-truth depth
  // Z (metres along the optical axis) of every pixel of the right image. Does not allocate.
  void render(const core::Pose2& robot_pose, double pan_rad, double time_s, std::uint32_t frame_index,
              cv::Mat& left, cv::Mat& right, cv::Mat* depth_right = nullptr);

  // Surfaces dropped because a column had more than sim.max_hits_per_column crossings.
  std::uint64_t dropped_hits() const { return dropped_hits_; }
  const TextureBank& textures() const { return textures_; }

  // Where the optical centre of the right (reference) and left camera are, and which way the
  // optical axis points, for a robot pose and pan angle.
  struct CameraPlacement {
    Eigen::Vector2d right_center;
    Eigen::Vector2d left_center;
    double height_m;
    double heading_rad;
  };
  CameraPlacement place_camera(const core::Pose2& robot_pose, double pan_rad) const;

  struct Hit {
    float depth_in = 0.0F;   // optical depth Z where the column's ray enters the object
    float depth_out = 0.0F;  // ... and leaves it (== depth_in for a wall)
    float z_min = 0.0F;
    float z_max = 0.0F;
    float texture_u_m = 0.0F;  // horizontal texture coordinate of the front face
    float gain = 1.0F;         // light region at the hit
    bool solid = false;        // has a top/bottom face between depth_in and depth_out
    const Surface* surface = nullptr;
  };

 private:
  void collect_hits(const Eigen::Vector2d& center, const Eigen::Vector2d& direction);
  void push_hit(const Hit& hit);
  void shade_column(const Eigen::Vector2d& center, const Eigen::Vector2d& direction, std::uint8_t* pixels,
                    float* depth);
  void fill_vertical(const Hit& hit, std::uint8_t* pixels, float* depth);
  void fill_horizontal(float plane_z, float from_depth, float to_depth, const Surface& surface, float gain,
                       const Eigen::Vector2d& center, const Eigen::Vector2d& direction, std::uint8_t* pixels,
                       float* depth);
  void fill_floor_and_ceiling(const Eigen::Vector2d& center, const Eigen::Vector2d& direction, std::uint8_t* pixels,
                              float* depth);
  void render_view(const Eigen::Vector2d& center, double heading, cv::Mat& image_transposed, cv::Mat* depth_transposed);
  void add_noise(cv::Mat& image, std::uint32_t frame_index, std::uint32_t camera_index);
  std::size_t raster_index(double x, double y) const;
  float floor_gain_at(double x, double y) const { return raster_gain_[raster_index(x, y)]; }

  const World& world_;
  core::CameraConfig camera_;
  core::SimConfig sim_;
  std::uint64_t noise_seed_;
  TextureBank textures_;
  double height_m_;
  // Floor raster (region index + 1, light gain) at kFloorRasterCell_m, made at start-up.
  Eigen::Vector2d raster_origin_;
  int raster_width_ = 0;
  int raster_height_ = 0;
  std::vector<float> raster_gain_;
  std::vector<std::uint8_t> raster_look_;  // index into floor_looks_
  // Each distinct (floor region, light gain) of the raster: its surface and gray-level map.
  struct FloorLook {
    Surface surface;
    float gain = 1.0F;
    float scale = 1.0F;
    float offset = 0.0F;
  };
  std::vector<FloorLook> floor_looks_;
  // The floor and the ceiling are at a fixed depth per image row (untilted camera): depth
  // (0 where the row does not see that plane) and texture mip level per row.
  std::vector<float> floor_row_depth_;
  std::vector<float> ceiling_row_depth_;
  std::vector<std::uint8_t> floor_row_level_;
  std::vector<std::uint8_t> ceiling_row_level_;
  // Per-column working set, sized once.
  std::vector<Hit> hits_;
  std::size_t hit_count_ = 0;
  std::vector<std::uint8_t> row_done_;
  std::vector<double> crossing_depth_;
  std::vector<double> crossing_u_;
  std::vector<Eigen::Vector2d> people_positions_;  // at the time of the current render
  std::vector<Eigen::Vector3d> prism_bounds_;      // bounding circle (x, y, radius) per prism
  std::vector<double> column_x_;                   // (u - cx) / f per image column
  std::vector<std::int16_t> noise_table_;
  cv::Mat left_transposed_;
  cv::Mat right_transposed_;
  cv::Mat depth_transposed_;
  std::uint64_t dropped_hits_ = 0;
};

}  // namespace stereoscout::host_sim
