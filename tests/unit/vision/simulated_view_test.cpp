// The 2.5D scan of the front end (dense matcher + scanner) on the closed-loop simulator's
// rendered pairs of the paper's lab (config/worlds/lab.yaml, sensor noise included), against
// the same scanner fed the ground-truth disparity of the rendering. This is the scan the
// whole stack sees: before the speckle filter, weak floor-tile texture under the simulator's
// image noise made the matcher report a ring of phantom obstacles 0.8-1.1 m around the robot
// in almost every column.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/system_config.hpp"
#include "stereoscout/host_sim/renderer.hpp"
#include "stereoscout/host_sim/world.hpp"
#include "stereoscout/test/paths.hpp"
#include "stereoscout/vision/calibration.hpp"
#include "stereoscout/vision/front_end.hpp"
#include "stereoscout/vision/obstacle_scan.hpp"

namespace stereoscout::vision {
namespace {

using Kind = core::DepthScanColumn::Kind;

// Forward-maps the right image's ground-truth depth to a left-referenced disparity map (the
// dense matcher's convention); where two surfaces land on one pixel the nearer one wins.
void disparity_from_right_depth(const cv::Mat& depth_right, double focal_baseline, cv::Mat& disparity_left) {
  disparity_left.setTo(kInvalidDisparity);
  for (int y = 0; y < depth_right.rows; ++y) {
    for (int x = 0; x < depth_right.cols; ++x) {
      const float depth = depth_right.at<float>(y, x);
      if (!(depth > 0.0F) || !std::isfinite(depth)) continue;
      const double d = focal_baseline / static_cast<double>(depth);
      const long column = std::lround(x + d);
      if (column >= depth_right.cols) continue;
      float& out = disparity_left.at<float>(y, static_cast<int>(column));
      out = std::max(out, static_cast<float>(d));
    }
  }
}

// The robot's immediate surroundings, where a phantom obstacle boxes it in.
constexpr double kNear_m = 2.5;
// A blank wall is placed where the floor's measured part ends (vision.scan_blank_wall_within_m):
// the last strip of floor by the wall's base is not matched, so that is up to this much
// nearer than the wall along the ray.
constexpr double kFloorEndShortfall_m = 0.6;

double range_of(const core::DepthScan& scan, const core::DepthScanColumn& column) {
  return std::hypot(column.x_robot_m - scan.origin_robot.x(), column.y_robot_m - scan.origin_robot.y());
}

struct ViewComparison {
  int columns = 0;
  int agreeing = 0;          // same kind; obstacles also within 10 % + 0.1 m
  int phantoms = 0;          // obstacle nearer than the truth's obstacle or free range by > 0.3 m
  int near_phantoms = 0;     // ... of them within kNear of the camera
  int free_space_phantoms = 0;  // ... of those, nearer by > kFloorEndShortfall_m (no wall base)
  int missed_walls = 0;      // free beyond the truth's obstacle by > 0.3 m (driving into it)
  int truth_obstacles = 0;
  int matched_obstacles = 0;  // truth obstacle columns that the scan reports as obstacle
};

ViewComparison compare(const core::DepthScan& scan, const core::DepthScan& truth) {
  ViewComparison result;
  for (std::size_t u = 0; u < scan.columns.size(); ++u) {
    const core::DepthScanColumn& seen = scan.columns[u];
    const core::DepthScanColumn& real = truth.columns[u];
    const double seen_range = range_of(scan, seen);
    const double real_range = range_of(truth, real);
    ++result.columns;
    if (seen.kind == real.kind && (seen.kind != Kind::obstacle || std::abs(seen_range - real_range) <= 0.1 * real_range + 0.1)) {
      ++result.agreeing;
    }
    if (real.kind == Kind::obstacle) {
      ++result.truth_obstacles;
      result.matched_obstacles += seen.kind == Kind::obstacle ? 1 : 0;
    }
    if (seen.kind == Kind::obstacle && real.kind != Kind::invalid && seen_range < real_range - 0.3) {
      ++result.phantoms;
      result.near_phantoms += seen_range < kNear_m ? 1 : 0;
      result.free_space_phantoms += seen_range < kNear_m && seen_range < real_range - kFloorEndShortfall_m ? 1 : 0;
    }
    if (seen.kind == Kind::free && real.kind == Kind::obstacle && seen_range > real_range + 0.3) {
      ++result.missed_walls;
    }
  }
  return result;
}

class SimulatedView : public ::testing::Test {
 protected:
  explicit SimulatedView(const char* world_path, const core::SystemConfig& config = core::SystemConfig{})
      : config_(config),
        world_(load(world_path)),
        renderer_(world_, config_.camera, config_.sim, static_cast<std::uint64_t>(config_.run.seed)),
        calibration_(calibration_from_config(config_.camera)),
        mount_{config_.camera.mount_x_m, config_.camera.mount_y_m, config_.camera.mount_height_m,
               core::degrees_to_radians(config_.camera.mount_tilt_deg)},
        front_end_(config_.vision, config_.robot, calibration_, mount_),
        truth_scanner_(scan_params_from_config(config_.vision, config_.robot), calibration_, mount_) {
    frame_.allocate(config_.camera.width_px, config_.camera.height_px);
    depth_.create(config_.camera.height_px, config_.camera.width_px, CV_32FC1);
    truth_disparity_.create(config_.camera.height_px, config_.camera.width_px, CV_32FC1);
    front_end_.allocate_scan(scan_);
    truth_scanner_.allocate(truth_);
  }

  static host_sim::World load(const char* world_path) {
    const host_sim::WorldLoad loaded = host_sim::load_world(test::source_path(world_path));
    EXPECT_TRUE(loaded.ok()) << loaded.error_text();
    return loaded.world;
  }

  ViewComparison look(double x_m, double y_m, double heading_deg, double pan_deg, std::uint32_t frame_index) {
    const double pan = core::degrees_to_radians(pan_deg);
    renderer_.render(core::Pose2{x_m, y_m, core::degrees_to_radians(heading_deg)}, pan, 0.0, frame_index, frame_.left, frame_.right,
                     &depth_);
    frame_.pan_rad = pan;
    front_end_.scan(frame_, scan_);
    disparity_from_right_depth(depth_, calibration_.focal_px * calibration_.baseline_m, truth_disparity_);
    truth_scanner_.compute(truth_disparity_, pan, 0, truth_);
    const ViewComparison result = compare(scan_, truth_);
    std::printf("view (%.1f, %.1f, %.0f deg, pan %.0f deg): agree %d/%d, phantoms %d (within %.1f m: %d), "
                "missed walls %d, obstacle columns %d/%d\n",
                x_m, y_m, heading_deg, pan_deg, result.agreeing, result.columns, result.phantoms, kNear_m,
                result.near_phantoms, result.missed_walls, result.matched_obstacles, result.truth_obstacles);
    return result;
  }

  const core::SystemConfig config_;
  host_sim::World world_;
  host_sim::StereoRenderer renderer_;
  StereoCalibration calibration_;
  core::CameraMount mount_;
  VisionFrontEnd front_end_;
  ObstacleScanner truth_scanner_;
  core::StereoFrame frame_;
  cv::Mat depth_;
  cv::Mat truth_disparity_;
  core::DepthScan scan_;
  core::DepthScan truth_;
};

class SimulatedLabView : public SimulatedView {
 protected:
  SimulatedLabView() : SimulatedView("config/worlds/lab.yaml") {}
};

class SimulatedOfficeView : public SimulatedView {
 protected:
  SimulatedOfficeView() : SimulatedView("config/worlds/office.yaml") {}
};

// Views of textured surfaces (brick wall, bookcases, tables, the tiled floor): the scan must
// agree with the ground-truth scan column by column: at least 90 % of the columns of the same
// kind (obstacle ranges within 10 % + 0.1 m). Phantoms (an obstacle more than 0.3 m nearer
// than the truth's obstacle or free range): at most 1 % of the columns within 2.5 m, 5 % in
// all. The far ones left are floor points 3-5 m away lifted above the scanner's 5 cm floor
// tolerance by 0.5-1 px of disparity error (at 4 m, 0.6 px is 5 cm of height).
TEST_F(SimulatedLabView, ScanAgreesWithGroundTruthDepth) {
  struct View {
    double x, y, heading, pan;
  };
  const View views[] = {{2.5, 2.5, 30.0, 0.0}, {2.5, 2.5, 30.0, 90.0}, {5.0, 4.0, 0.0, 0.0}, {8.0, 6.0, 45.0, 0.0}};
  std::uint32_t frame = 0;
  for (const View& view : views) {
    const ViewComparison result = look(view.x, view.y, view.heading, view.pan, frame++);
    EXPECT_GE(result.agreeing, result.columns * 90 / 100) << "view " << frame - 1;
    EXPECT_LE(result.near_phantoms, result.columns / 100) << "view " << frame - 1;
    EXPECT_LE(result.phantoms, result.columns * 5 / 100) << "view " << frame - 1;
    EXPECT_LE(result.missed_walls, result.columns * 2 / 100) << "view " << frame - 1;
  }
}

// Every direction from the start pose, untextured walls included (the scene of the phantom
// ring): a column the matcher cannot measure may be unknown or free short of the wall, but
// nothing stands within 2.5 m of the start pose, so no column may report an obstacle within
// 2 m, at most 3 % of the columns may hold a phantom at all, and none free space through a wall.
TEST_F(SimulatedLabView, NoPhantomObstaclesAroundTheStartPose) {
  int columns = 0;
  int phantoms = 0;
  int near_obstacles = 0;
  for (int pan_deg = 0; pan_deg < 360; pan_deg += 90) {
    const ViewComparison result = look(2.5, 2.5, 30.0, static_cast<double>(pan_deg), static_cast<std::uint32_t>(pan_deg));
    columns += result.columns;
    phantoms += result.phantoms;
    EXPECT_LE(result.missed_walls, result.columns * 2 / 100) << "pan " << pan_deg;
    for (std::size_t u = 0; u < scan_.columns.size(); ++u) {
      ASSERT_FALSE(truth_.columns[u].kind == Kind::obstacle && range_of(truth_, truth_.columns[u]) < kNear_m);
      near_obstacles += scan_.columns[u].kind == Kind::obstacle && range_of(scan_, scan_.columns[u]) < 2.0 ? 1 : 0;
    }
  }
  EXPECT_LE(phantoms, columns * 3 / 100);
  EXPECT_EQ(near_obstacles, 0);
}

// A walker ahead (the lab's person 2 at t = 0, at (2, 12.5), the robot facing them from the
// east): the scan sees them at the camera's height, which the explorer's scan guard uses,
// down to about 1 m between the centres. Nearer, the person's surface is closer to the camera
// than focal * baseline / dense_num_disparities (0.63 m) and the matcher finds nothing there,
// so the guard must look farther than that (explore.scan_guard_distance_m).
TEST_F(SimulatedLabView, AWalkerAheadIsSeenAtCameraHeightUntilNearerThanTheMatcherReaches) {
  const Eigen::Vector2d person(2.0, 12.5);
  auto person_columns_at_camera_height = [&](double centres_apart_m) {
    look(person.x() + centres_apart_m, person.y(), 180.0, 0.0, 1);
    int columns = 0;
    for (const core::DepthScanColumn& column : scan_.columns) {
      // Robot frame: the robot faces the person, who stands centres_apart_m straight ahead.
      const double from_person = std::hypot(column.x_robot_m - centres_apart_m, column.y_robot_m);
      if (column.kind == Kind::obstacle && column.obstacle_at_camera_height && from_person < 0.4) ++columns;
    }
    return columns;
  };
  for (const double apart_m : {2.0, 1.5, 1.0}) EXPECT_GE(person_columns_at_camera_height(apart_m), 100) << apart_m;
  EXPECT_LE(person_columns_at_camera_height(0.6), 5);
}

// The office corridor's walls are blank (contrast 0.2: no disparity). Across the corridor,
// along it and into an office door: no column may report free space through a wall. Seen at
// an angle, a blank wall is an obstacle where the floor ends, a little short of it (no free-space
// phantom within 2.5 m); head-on from the corridor's middle the floor before it is in the
// camera's blind zone, and the wall stays unseen.
TEST_F(SimulatedOfficeView, NoFreeSpaceThroughBlankWalls) {
  struct View {
    double x, y, heading, pan;
    bool wall_found;  // at least a quarter of the truth's obstacle columns
  };
  const View views[] = {{4.0, 5.1, 90.0, 0.0, false}, {4.0, 5.1, -90.0, 0.0, false}, {10.0, 5.1, 0.0, 0.0, true},
                        {10.0, 5.1, 60.0, 0.0, true},  {12.0, 5.0, 100.0, 0.0, true}, {20.0, 5.3, -120.0, 0.0, true}};
  std::uint32_t frame = 0;
  for (const View& view : views) {
    const ViewComparison result = look(view.x, view.y, view.heading, view.pan, frame++);
    EXPECT_LE(result.missed_walls, result.columns * 2 / 100) << "view " << frame - 1;
    EXPECT_EQ(result.free_space_phantoms, 0) << "view " << frame - 1;
    if (view.wall_found) {
      EXPECT_GE(result.matched_obstacles, result.truth_obstacles / 4) << "view " << frame - 1;
    }
  }
}

// Faced head-on from 1.4 m (the corridor's north wall from y = 4.8, its south wall from
// y = 5.4, between the doors), the tiles before a blank wall are not
// matched at all, so the floor's end gives nothing; the brightness step at the wall's base
// puts the wall where it stands, in the columns whose base lies within 1.5 m.
TEST_F(SimulatedOfficeView, ABlankWallFacedHeadOnIsSeenAtItsBase) {
  struct View {
    double x, y, heading;
  };
  const View views[] = {{3.0, 4.7, 90.0}, {10.0, 4.7, 90.0}, {7.0, 5.5, -90.0}};
  std::uint32_t frame = 0;
  for (const View& view : views) {
    const ViewComparison result = look(view.x, view.y, view.heading, 0.0, frame++);
    // Without the wall's base: 34-36 % and 23-26 % (the floor's end, 0.3-0.6 m short, in the
    // side columns); with it 64-65 % and 54 %.
    EXPECT_GE(result.matched_obstacles, result.truth_obstacles * 55 / 100) << "view " << frame - 1;
    EXPECT_GE(result.agreeing, result.columns * 45 / 100) << "view " << frame - 1;
    EXPECT_EQ(result.free_space_phantoms, 0) << "view " << frame - 1;
  }
}

class SimulatedClutterView : public SimulatedView {
 protected:
  SimulatedClutterView() : SimulatedView("config/worlds/clutter.yaml") {}
};

// Looking south along the clutter hall's half-height dividing wall (x = 7, y 0-5) from just
// north of its end: beside the wall's edge the two cameras see differently, the matcher is
// confused on the tiles and the poster, and the floor's matched part ends 1.0-1.5 m away with
// open floor beyond. Nothing there lacks texture, so the blank-wall rule must not fire (it put
// a wall of obstacle cells across the passage west of the dividing wall, 11-12 columns in this
// view, before it asked whether the view above the floor's end is blank). As for the lab's
// views, at most 1 % of the columns may hold a phantom within 2.5 m (x86-64 gives none, the
// arm64 build 2).
TEST_F(SimulatedClutterView, NoBlankWallWhereTheFloorEndsBesideAnEdge) {
  const ViewComparison result = look(7.02, 5.72, -90.0, 0.0, 0);
  EXPECT_LE(result.near_phantoms, result.columns / 100);
  EXPECT_GE(result.agreeing, result.columns * 80 / 100);
}

// Views from the 1.2 m gap between the dividing wall's end (7, 5) and the low cylinder at
// (7.5, 6.5), facing south-east, where the L-shaped rack's book spines stand 1.6-2 m away
// (true poses of clutter seed 2 at 279.7-285.8 s, three noise draws each). Look-alike spines
// matched at a wrong disparity of 50-60 px form regions of 100-400 pixels, past the speckle
// filter's pixel limit, that put phantoms 0.67-0.83 m ahead and closed the gap in the map.
// Their surface at that depth is 8-16 cm^2 with nothing as near around them, so the area rule
// (vision.dense_speckle_min_area_m2) removes them: no phantom within 1.2 m in any of the 12
// views, against 40 columns without the rule (x86-64 and arm64 alike).
struct GapView {
  double x_m, y_m, heading_deg;
};
constexpr GapView kGapViews[] = {{6.66, 5.80, -49.0}, {6.78, 5.71, -29.0}, {6.87, 5.67, -23.0}, {7.10, 5.60, -17.0}};
constexpr double kAhead_m = 1.2;

// A surface's edge may fall one column either side in the scan and in the ground truth (the
// arm64 build's rendering puts the dividing wall's end one column over in one view): a column
// whose obstacle is more than 0.3 m nearer than the truth is a phantom unless a neighbouring
// column's truth ends there (no more than 0.3 m beyond it).
bool truth_reaches(const core::DepthScan& scan, const core::DepthScan& truth, std::size_t u, std::size_t v) {
  return truth.columns[v].kind != Kind::invalid &&
         range_of(scan, scan.columns[u]) >= range_of(truth, truth.columns[v]) - 0.3;
}

int phantoms_within(double range_m, const core::DepthScan& scan, const core::DepthScan& truth) {
  int count = 0;
  const std::size_t columns = scan.columns.size();
  for (std::size_t u = 0; u < columns; ++u) {
    if (scan.columns[u].kind != Kind::obstacle || truth.columns[u].kind == Kind::invalid ||
        range_of(scan, scan.columns[u]) >= range_m || truth_reaches(scan, truth, u, u)) {
      continue;
    }
    const bool edge = (u > 0 && truth_reaches(scan, truth, u, u - 1)) ||
                      (u + 1 < columns && truth_reaches(scan, truth, u, u + 1));
    count += edge ? 0 : 1;
  }
  return count;
}

// Phantom columns within kAhead_m over the gap views, and the rack's columns the scan still
// reports as obstacles (of the ground truth's).
struct GapViewsResult {
  int near_phantoms = 0;
  int matched_obstacles = 0;
  int truth_obstacles = 0;
};

class SimulatedClutterGapViews : public SimulatedView {
 protected:
  explicit SimulatedClutterGapViews(const core::SystemConfig& config = core::SystemConfig{})
      : SimulatedView("config/worlds/clutter.yaml", config) {}
  GapViewsResult look_from_the_gap() {
    GapViewsResult result;
    for (std::uint32_t frame = 0; frame < 3; ++frame) {
      for (const GapView& view : kGapViews) {
        const ViewComparison seen = look(view.x_m, view.y_m, view.heading_deg, 0.0, frame);
        result.near_phantoms += phantoms_within(kAhead_m, scan_, truth_);
        result.matched_obstacles += seen.matched_obstacles;
        result.truth_obstacles += seen.truth_obstacles;
      }
    }
    std::printf("gap views: %d phantom columns within %.1f m, %d of %d obstacle columns seen\n", result.near_phantoms,
                kAhead_m, result.matched_obstacles, result.truth_obstacles);
    return result;
  }
};

TEST_F(SimulatedClutterGapViews, NoPhantomWhereLookAlikeBookSpinesMatchAtAWrongDepth) {
  const GapViewsResult result = look_from_the_gap();
  EXPECT_EQ(result.near_phantoms, 0);
  EXPECT_GE(result.matched_obstacles, result.truth_obstacles * 90 / 100);
}

core::SystemConfig without_the_area_rule() {
  core::SystemConfig config;
  config.vision.dense_speckle_min_area_m2 = 0.0;
  return config;
}

class SimulatedClutterGapViewsWithoutTheAreaRule : public SimulatedClutterGapViews {
 protected:
  SimulatedClutterGapViewsWithoutTheAreaRule() : SimulatedClutterGapViews(without_the_area_rule()) {}
};

TEST_F(SimulatedClutterGapViewsWithoutTheAreaRule, LookAlikeBookSpinesStandAsPhantomsNearTheCamera) {
  EXPECT_GE(look_from_the_gap().near_phantoms, 20);
}

// The stereo matches the filter triangulates, on rendered views of the lab, against the
// rendering's depth where the surface is smooth (no depth edge within 2 px). A landmark's
// depth from one match is nearly unbiased: the median disparity error is about 0.001 px and
// the mean relative depth error of the matches within 1.5 px of the truth +0.15 to +0.35 %.
// What is biased is fusing them as the filter does, each weighed by the inverse of its
// covariance taken at its measured disparity (depth variance ~ 1 / d^4): nearer-measured
// matches count more, and the fused depth comes out none short within 4 m, 0.5 % at 4-8 m and
// 2 % beyond 8 m (docs/results.md, sixty-third session: every run's trajectory is about 1 % smaller
// than the truth). This test checks both: one by one within 0.6 %, fused by 1 / d^4 at least 1 %
// shorter than one by one beyond 8 m and 0.3 % at 4-8 m.
TEST_F(SimulatedLabView, SparseStereoDepthsAreUnbiasedButInverseVarianceFusionIsShort) {
  const double focal_baseline = calibration_.focal_px * calibration_.baseline_m;
  constexpr double kGate_px = 1.5;  // a match farther off than this is an outlier, not noise
  constexpr int kBins = 3;          // true disparity [0, 5), [5, 10), [10, inf) px
  double plain_sum[kBins] = {}, weighted_sum[kBins] = {}, weight_sum[kBins] = {};
  int count[kBins] = {};
  std::vector<double> disparity_errors;
  core::FixedVector<core::LandmarkObservation> observations(front_end_.max_observations());
  std::uint32_t frame_index = 1;
  for (const double x_m : {4.0, 9.0, 14.0}) {
    for (const double y_m : {4.0, 11.0}) {
      for (double heading_deg = 0.0; heading_deg < 360.0; heading_deg += 60.0) {
        look(x_m, y_m, heading_deg, 0.0, frame_index++);
        observations.clear();
        ASSERT_TRUE(front_end_.observe_landmarks(frame_, observations).ok());
        for (const StereoMatch& match : front_end_.last_matches()) {
          const Keypoint& right = front_end_.last_right_keys()[match.right_index];
          const int column = static_cast<int>(std::lround(right.x_px));
          const int row = static_cast<int>(std::lround(right.y_px));
          const cv::Rect window(column - 2, row - 2, 5, 5);
          if ((window & cv::Rect(0, 0, depth_.cols, depth_.rows)) != window) continue;
          double lowest = 0.0, highest = 0.0;
          cv::minMaxLoc(depth_(window), &lowest, &highest);
          const double depth = depth_.at<float>(row, column);
          if (!(lowest > 0.0) || !std::isfinite(highest) || highest - lowest > 0.05 * depth) continue;
          const double true_disparity = focal_baseline / depth;
          const double error_px = match.disparity_px - true_disparity;
          disparity_errors.push_back(error_px);
          if (std::abs(error_px) > kGate_px) continue;
          const int bin = std::min(kBins - 1, static_cast<int>(true_disparity / 5.0));
          const double relative_error = focal_baseline / match.disparity_px / depth - 1.0;
          const double weight = std::pow(static_cast<double>(match.disparity_px), 4.0);
          plain_sum[bin] += relative_error;
          weighted_sum[bin] += weight * relative_error;
          weight_sum[bin] += weight;
          ++count[bin];
        }
      }
    }
  }
  ASSERT_GT(disparity_errors.size(), 5000U);
  std::nth_element(disparity_errors.begin(), disparity_errors.begin() + static_cast<long>(disparity_errors.size() / 2),
                   disparity_errors.end());
  const double median_error_px = disparity_errors[disparity_errors.size() / 2];
  std::printf("matches %zu, median disparity error %.4f px\n", disparity_errors.size(), median_error_px);
  EXPECT_LT(std::abs(median_error_px), 0.02);
  for (int bin = 0; bin < kBins; ++bin) {
    ASSERT_GT(count[bin], 500) << bin;
    const double plain = plain_sum[bin] / count[bin];
    const double fused = weighted_sum[bin] / weight_sum[bin];
    std::printf("true disparity from %d px: %d matches, depth error %.2f %% one by one, %.2f %% fused by 1 / d^4\n",
                5 * bin, count[bin], 100.0 * plain, 100.0 * fused);
    EXPECT_LT(std::abs(plain), 0.006) << bin;
    constexpr double kFusedShortfall[kBins] = {0.01, 0.003, 0.0};  // beyond 8 m, 4-8 m, nearer
    if (kFusedShortfall[bin] > 0.0) {
      EXPECT_LT(fused, plain - kFusedShortfall[bin]) << bin;
    }
  }
}

}  // namespace
}  // namespace stereoscout::vision
