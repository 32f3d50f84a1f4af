#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include <algorithm>
#include <cmath>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/core/system_config.hpp"
#include "stereoscout/host_sim/renderer.hpp"
#include "test_worlds.hpp"

namespace stereoscout::host_sim {
namespace {

using testing::load_or_fail;
using testing::room_yaml;
using testing::source_path;

struct Pair {
  cv::Mat left;
  cv::Mat right;
  cv::Mat depth;
};

Pair render(const World& world, const core::Pose2& pose, const core::SimConfig& sim = {}, std::uint64_t seed = 1,
            std::uint32_t frame = 0, double pan = 0.0) {
  const core::CameraConfig camera;
  StereoRenderer renderer(world, camera, sim, seed);
  Pair pair{cv::Mat(camera.height_px, camera.width_px, CV_8UC1), cv::Mat(camera.height_px, camera.width_px, CV_8UC1),
            cv::Mat(camera.height_px, camera.width_px, CV_32FC1)};
  renderer.render(pose, pan, 0.0, frame, pair.left, pair.right, &pair.depth);
  return pair;
}

World lab() {
  const WorldLoad load = load_world(source_path("config/worlds/lab.yaml"));
  EXPECT_TRUE(load.ok()) << load.error_text();
  return load.world;
}

std::vector<cv::KeyPoint> sift_keypoints(const cv::Mat& image, cv::Mat* descriptors = nullptr) {
  cv::Ptr<cv::SIFT> sift = cv::SIFT::create();
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat unused;
  sift->detectAndCompute(image, cv::noArray(), keypoints, descriptors != nullptr ? *descriptors : unused);
  return keypoints;
}

TEST(Renderer, DepthOfAWallAndTheFloorIsExact) {
  // The camera (0.1 m ahead of the robot centre, 0.6 m high) faces the wall at x = 10 from x = 2.
  const World world = load_or_fail(room_yaml("brick"));
  const Pair pair = render(world, core::Pose2{2.0, 3.0, 0.0});
  const core::CameraConfig camera;
  // Centre column at the horizon: the wall 7.9 m ahead along the optical axis.
  EXPECT_NEAR(pair.depth.at<float>(239, 320), 7.9F, 1e-4F);
  // Every wall pixel of a fronto-parallel wall has the same depth Z (not range).
  EXPECT_NEAR(pair.depth.at<float>(239, 200), 7.9F, 1e-4F);
  // Floor row r: Z = f h / (r - cy).
  for (int row : {300, 400, 479}) {
    const double expected = camera.focal_px * camera.mount_height_m / (row - camera.principal_y_px);
    EXPECT_NEAR(pair.depth.at<float>(row, 320), expected, 1e-4) << row;
  }
  // Ceiling row r: Z = f (h - ceiling) / (r - cy).
  const double ceiling_depth = camera.focal_px * (0.6 - 2.5) / (0 - camera.principal_y_px);
  EXPECT_NEAR(pair.depth.at<float>(0, 320), ceiling_depth, 1e-4);
}

TEST(Renderer, TriangulatedSiftMatchesAgreeWithGroundTruthDepth) {
  const World world = lab();
  const Pair pair = render(world, core::Pose2{2.5, 2.5, core::degrees_to_radians(30.0)});
  const core::CameraConfig camera;
  cv::Mat left_descriptors;
  cv::Mat right_descriptors;
  const auto left = sift_keypoints(pair.left, &left_descriptors);
  const auto right = sift_keypoints(pair.right, &right_descriptors);
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> matches;
  matcher.knnMatch(right_descriptors, left_descriptors, matches, 2);
  int used = 0;
  int agreeing = 0;
  for (const auto& candidates : matches) {
    if (candidates.size() < 2 || candidates[0].distance > 0.7F * candidates[1].distance) continue;
    const cv::Point2f r = right[static_cast<std::size_t>(candidates[0].queryIdx)].pt;
    const cv::Point2f l = left[static_cast<std::size_t>(candidates[0].trainIdx)].pt;
    const double disparity = l.x - r.x;
    if (std::abs(l.y - r.y) > 1.0F || disparity < 1.0) continue;  // epipolar constraint, in front
    // Ground truth disparity f B / Z (paper eq. 3, right image as reference); a keypoint on a
    // depth edge may take either side, so the nearest of its 3x3 neighbours counts.
    double best_error = 1e9;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int row = std::clamp(cvRound(r.y) + dy, 0, camera.height_px - 1);
        const int column = std::clamp(cvRound(r.x) + dx, 0, camera.width_px - 1);
        const double truth = camera.focal_px * camera.baseline_m / pair.depth.at<float>(row, column);
        best_error = std::min(best_error, std::abs(disparity - truth));
      }
    }
    ++used;
    // Twice the paper's disparity noise (sigma_d = 0.5 px).
    if (best_error <= 1.0) ++agreeing;
  }
  EXPECT_GT(used, 100);
  EXPECT_GT(agreeing, used * 90 / 100) << agreeing << " of " << used;
}

TEST(Renderer, DisparityOfEveryPixelMatchesTheOtherImage) {
  // Without noise, the left pixel at u + fB/Z shows the same surface as the right pixel u.
  core::SimConfig sim;
  sim.image_noise_sigma = 0.0;
  const World world = load_or_fail(room_yaml("poster", "blank", "blank"));
  const Pair pair = render(world, core::Pose2{2.0, 3.0, 0.0}, sim);
  const core::CameraConfig camera;
  int compared = 0;
  int equal = 0;
  for (int row = 140; row < 200; ++row) {  // wall rows
    for (int u = 20; u < 600; u += 7) {
      const double disparity = camera.focal_px * camera.baseline_m / pair.depth.at<float>(row, u);
      const int left_u = static_cast<int>(std::lround(u + disparity));
      ++compared;
      if (std::abs(pair.left.at<std::uint8_t>(row, left_u) - pair.right.at<std::uint8_t>(row, u)) <= 2) ++equal;
    }
  }
  EXPECT_GT(equal, compared * 9 / 10) << equal << " of " << compared;
}

TEST(Renderer, LabViewHasHundredsOfSiftKeypointsAndABlankRoomAlmostNone) {
  const Pair lab_view = render(lab(), core::Pose2{2.5, 2.5, core::degrees_to_radians(30.0)});
  const std::size_t lab_keypoints = sift_keypoints(lab_view.right).size();
  EXPECT_GE(lab_keypoints, 300U);
  // Facing a blank wall close up: the whole image is wall.
  const World blank = load_or_fail(room_yaml("blank", "blank", "blank"));
  const Pair blank_view = render(blank, core::Pose2{8.5, 3.0, 0.0});
  const std::size_t blank_keypoints = sift_keypoints(blank_view.right).size();
  EXPECT_LE(blank_keypoints, 10U);
  std::printf("SIFT keypoints: lab view %zu, blank wall %zu\n", lab_keypoints, blank_keypoints);
}

TEST(Renderer, EveryTexturedSurfaceGivesKeypoints) {
  // One blank 10 m x 6 m room per texture, side by side along x; each room's east wall has
  // the texture and fills the view from 2.4 m.
  const char* textures[] = {"poster", "books", "brick", "wood", "noise"};
  std::string yaml = "start: [1, 1, 0]\nfloor: {texture: blank}\nceiling: {texture: blank}\nwalls:\n";
  for (int i = 0; i < 5; ++i) {
    const std::string x0 = std::to_string(10 * i);
    const std::string x1 = std::to_string(10 * i + 10);
    yaml += "  - {points: [[" + x1 + ", 6], [" + x0 + ", 6], [" + x0 + ", 0], [" + x1 + ", 0]], texture: blank}\n";
    yaml += "  - {points: [[" + x1 + ", 0], [" + x1 + ", 6]], texture: " + textures[i] + ", brightness: 0.5, contrast: 0.8}\n";
  }
  const World world = load_or_fail(yaml);
  const core::CameraConfig camera;
  StereoRenderer renderer(world, camera, core::SimConfig{}, 1);
  cv::Mat left(camera.height_px, camera.width_px, CV_8UC1);
  cv::Mat right(camera.height_px, camera.width_px, CV_8UC1);
  for (int i = 0; i < 5; ++i) {
    renderer.render(core::Pose2{10.0 * i + 7.5, 3.0, 0.0}, 0.0, 0.0, 0, left, right);
    EXPECT_GE(sift_keypoints(right).size(), 100U) << textures[i];
  }
}

TEST(Renderer, SameSeedGivesIdenticalImagesAndNoiseDependsOnSeedAndFrame) {
  const World world = lab();
  const core::Pose2 pose{3.0, 6.0, core::degrees_to_radians(170.0)};
  const Pair first = render(world, pose, {}, 7, 3);
  const Pair second = render(world, pose, {}, 7, 3);
  EXPECT_EQ(cv::norm(first.left, second.left, cv::NORM_L1), 0.0);
  EXPECT_EQ(cv::norm(first.right, second.right, cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(first.right, render(world, pose, {}, 8, 3).right, cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(first.right, render(world, pose, {}, 7, 4).right, cv::NORM_L1), 0.0);
}

TEST(Renderer, WindowSaturatesAndExposureScalesBrightness) {
  const World world = lab();
  // From the middle of the east room, looking south at the window (x 12-16, 0.9-2.2 m high).
  const core::Pose2 pose{14.0, 5.0, core::degrees_to_radians(-90.0)};
  const Pair view = render(world, pose);
  EXPECT_EQ(view.right.at<std::uint8_t>(200, 320), 255);
  core::SimConfig dark;
  dark.exposure = 0.5;
  dark.image_noise_sigma = 0.0;
  core::SimConfig normal;
  normal.image_noise_sigma = 0.0;
  const double mean_dark = cv::mean(render(world, core::Pose2{3, 3, 1.0}, dark).right)[0];
  const double mean_normal = cv::mean(render(world, core::Pose2{3, 3, 1.0}, normal).right)[0];
  EXPECT_NEAR(mean_dark / mean_normal, 0.5, 0.05);
}

TEST(Renderer, TableTopIsSeenFromBelowAndTheBoxFromAbove) {
  core::SimConfig sim;
  sim.image_noise_sigma = 0.0;
  const World world = load_or_fail(room_yaml("blank", "blank", "blank") +
                                    "boxes:\n  - {center: [5, 3], size: [1, 1], z: [0.72, 0.76], texture: wood}\n"
                                    "  - {center: [5, 3], size: [1, 1], z: [0, 0.1], texture: wood}\n");
  const Pair view = render(world, core::Pose2{2.4, 3.0, 0.0});  // camera at x = 2.5, 2 m from the near faces
  const core::CameraConfig camera;
  // Underside of the table top at z = 0.72: rows above the horizon, Z in [2, 3].
  const double row_under = camera.principal_y_px + camera.focal_px * (0.6 - 0.72) / 2.5;
  EXPECT_NEAR(view.depth.at<float>(static_cast<int>(std::lround(row_under)), 320), 2.5, 0.05);
  // Top of the low box at z = 0.1: below the horizon, Z in [2, 3].
  const double row_top = camera.principal_y_px + camera.focal_px * (0.6 - 0.1) / 2.5;
  EXPECT_NEAR(view.depth.at<float>(static_cast<int>(std::lround(row_top)), 320), 2.5, 0.05);
}

// Descriptors of `a` that have a look-alike in `b`: the nearest is within the front end's
// match distance (vision.index_match_distance, 180) and clearly nearer than the second.
int look_alikes(const cv::Mat& a, const cv::Mat& b) {
  cv::BFMatcher matcher(cv::NORM_L2);
  std::vector<std::vector<cv::DMatch>> nearest;
  matcher.knnMatch(a, b, nearest, 2);
  int count = 0;
  for (const auto& pair : nearest) {
    if (pair.size() == 2 && pair[0].distance < 180.0F && pair[0].distance < 0.8F * pair[1].distance) ++count;
  }
  return count;
}

TEST(Renderer, WithTextureVariantsTwoPlacesOfOneTextureDoNotLookAlike) {
  // A 40 m wall of posters, seen square from 2 m (3.2 m of it in view) at five pairs of places
  // two tiles (5.12 m) apart. With one tile the two views of a pair show the same texels; with
  // variants each 2.56 m cell of the wall shows one of 16 looks (8 tiles, mirrored or not), so
  // a pair shares a look only by chance.
  struct Views {
    int keypoints = 0;
    int alike = 0;
    int pairs_mostly_alike = 0;
  };
  const auto wall_views = [](int variants) {
    const World world = load_or_fail("seed: 5\ntexture_variants: " + std::to_string(variants) +
                                     "\nstart: [1, 1, 0]\nfloor: {texture: blank}\nceiling: {texture: blank}\n"
                                     "walls:\n  - {points: [[0, 6], [40, 6]], texture: poster, contrast: 0.8}\n");
    core::SimConfig sim;
    sim.image_noise_sigma = 0.0;
    const core::CameraConfig camera;
    StereoRenderer renderer(world, camera, sim, 1);
    cv::Mat left(camera.height_px, camera.width_px, CV_8UC1);
    cv::Mat right(camera.height_px, camera.width_px, CV_8UC1);
    Views views;
    for (double x = 3.0; x < 30.0; x += 6.5) {
      cv::Mat here;
      cv::Mat there;
      renderer.render(core::Pose2{x, 4.0, core::kPi / 2.0}, 0.0, 0.0, 0, left, right);
      sift_keypoints(right, &here);
      renderer.render(core::Pose2{x + 5.12, 4.0, core::kPi / 2.0}, 0.0, 0.0, 0, left, right);
      sift_keypoints(right, &there);
      const int alike = look_alikes(here, there);
      views.keypoints += here.rows;
      views.alike += alike;
      views.pairs_mostly_alike += 2 * alike > here.rows ? 1 : 0;
    }
    return views;
  };
  const Views tile = wall_views(1);
  const Views variants = wall_views(8);
  std::printf("keypoints with a look-alike two tiles along: one tile %d of %d, 8 variants %d of %d\n", tile.alike,
              tile.keypoints, variants.alike, variants.keypoints);
  EXPECT_EQ(tile.pairs_mostly_alike, 5);
  EXPECT_GT(tile.alike, 9 * tile.keypoints / 10);
  EXPECT_LE(variants.pairs_mostly_alike, 1);
  EXPECT_LT(variants.alike, variants.keypoints / 4);
  // The variants are drawn by the texture's own generator: as many keypoints, give or take.
  EXPECT_GT(variants.keypoints, tile.keypoints / 2);
}

TEST(Renderer, OneTextureVariantRendersAsTheOneTile) {
  // A world without the key and one with texture_variants: 1 are the same world.
  const std::string room = testing::room_yaml("poster", "carpet");
  const core::Pose2 pose{6.0, 2.0, 0.7};
  const Pair plain = render(load_or_fail(room), pose);
  const Pair one = render(load_or_fail("texture_variants: 1\n" + room), pose);
  const Pair eight = render(load_or_fail("texture_variants: 8\n" + room), pose);
  EXPECT_EQ(cv::norm(plain.right, one.right, cv::NORM_L1), 0.0);
  EXPECT_GT(cv::norm(plain.right, eight.right, cv::NORM_L1), 0.0);
}

TEST(Renderer, PanTurnsTheView) {
  core::SimConfig sim;
  sim.image_noise_sigma = 0.0;
  const World world = lab();
  const Pair panned = render(world, core::Pose2{5.0, 5.0, 0.0}, sim, 1, 0, core::kPi / 2.0);
  const Pair turned = render(world, core::Pose2{5.0, 5.0, core::kPi / 2.0}, sim, 1, 0, 0.0);
  // Same heading; the camera centre differs by the mount offset only (0.1 m), so depths are close.
  EXPECT_NEAR(panned.depth.at<float>(239, 320), turned.depth.at<float>(239, 320), 0.15);
}

TEST(Renderer, PeopleWalkThroughTheView) {
  core::SimConfig sim;
  sim.image_noise_sigma = 0.0;
  // A person walks along y = 3 from x = 4 to x = 8 and back at 1 m/s; the camera at x = 2.1
  // looks along the same line (east), so the person is straight ahead at 1.9 m - 0.25 m at t = 0.
  const World world = load_or_fail(room_yaml("brick") + "people:\n  - {waypoints: [[4, 3], [8, 3]], speed: 1.0}\n");
  const core::CameraConfig camera;
  StereoRenderer renderer(world, camera, sim, 1);
  cv::Mat left(camera.height_px, camera.width_px, CV_8UC1);
  cv::Mat right(camera.height_px, camera.width_px, CV_8UC1);
  cv::Mat depth(camera.height_px, camera.width_px, CV_32FC1);
  renderer.render(core::Pose2{2.0, 3.0, 0.0}, 0.0, 0.0, 0, left, right, &depth);
  EXPECT_NEAR(depth.at<float>(239, 320), 1.65F, 1e-3F);
  renderer.render(core::Pose2{2.0, 3.0, 0.0}, 0.0, 2.0, 0, left, right, &depth);
  EXPECT_NEAR(depth.at<float>(239, 320), 3.65F, 1e-3F);
  // Above the head (1.7 m high: from row 119 down) the ceiling shows, Z = f (h - 2.5) / (r - cy).
  EXPECT_NEAR(depth.at<float>(100, 320), 400.0 * (0.6 - 2.5) / (100 - 239.5), 1e-3);
}

TEST(Renderer, RenderingDoesNotAllocate) {
  for (int variants : {1, 8}) {
    World world = lab();
    world.texture_variants = variants;
    const core::CameraConfig camera;
    StereoRenderer renderer(world, camera, core::SimConfig{}, 1);
    cv::Mat left(camera.height_px, camera.width_px, CV_8UC1);
    cv::Mat right(camera.height_px, camera.width_px, CV_8UC1);
    cv::Mat depth(camera.height_px, camera.width_px, CV_32FC1);
    renderer.render(core::Pose2{3, 3, 0}, 0.0, 0.0, 0, left, right, &depth);
    const core::AllocationScope scope;
    renderer.render(core::Pose2{12, 7, 2.0}, 0.3, 5.0, 1, left, right, &depth);
    EXPECT_EQ(scope.allocations(), 0U) << variants << " texture variants";
  }
}

TEST(Renderer, TiltedCameraIsRefusedWithTheKey) {
  core::CameraConfig camera;
  EXPECT_TRUE(check_camera_supported(camera).empty());
  camera.mount_tilt_deg = 10.0;
  EXPECT_EQ(check_camera_supported(camera).rfind("camera.mount_tilt_deg:", 0), 0U);
}

}  // namespace
}  // namespace stereoscout::host_sim
