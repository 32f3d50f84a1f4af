#include <gtest/gtest.h>

#include <cmath>

#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/random.hpp"
#include "stereoscout/vision/calibration.hpp"

namespace stereoscout::vision {
namespace {

StereoCalibration paper_camera() { return calibration_from_config(core::CameraConfig{}); }

TEST(Triangulation, Equation3) {
  const StereoCalibration camera = paper_camera();
  // 10 px disparity with f = 400 px, B = 0.1 m: Z = 4 m. 40 px right of and 20 px above the
  // principal point: X = 40 * 4 / 400 = 0.4 m, Y = -0.2 m.
  const Eigen::Vector3d point = triangulate_point(camera, 319.5 + 40.0, 239.5 - 20.0, 10.0);
  EXPECT_DOUBLE_EQ(point.z(), 4.0);
  EXPECT_DOUBLE_EQ(point.x(), 0.4);
  EXPECT_DOUBLE_EQ(point.y(), -0.2);
}

TEST(Triangulation, CovarianceIsJacobianTimesPixelNoise) {
  const StereoCalibration camera = paper_camera();
  const StereoNoise noise{10.0, 10.0, 0.5};
  const double x = 400.0;
  const double y = 100.0;
  const double d = 12.5;
  const StereoPoint result = triangulate(camera, noise, x, y, d);
  // Central differences of eq. 3 with respect to (u, v, d).
  Eigen::Matrix3d jacobian;
  const double h = 1e-4;
  jacobian.col(0) = (triangulate_point(camera, x + h, y, d) - triangulate_point(camera, x - h, y, d)) / (2 * h);
  jacobian.col(1) = (triangulate_point(camera, x, y + h, d) - triangulate_point(camera, x, y - h, d)) / (2 * h);
  jacobian.col(2) = (triangulate_point(camera, x, y, d + h) - triangulate_point(camera, x, y, d - h)) / (2 * h);
  const Eigen::Matrix3d expected = jacobian * Eigen::Vector3d(100.0, 100.0, 0.25).asDiagonal() * jacobian.transpose();
  EXPECT_LT((result.covariance - expected).norm(), 1e-6 * expected.norm());
  EXPECT_TRUE(core::is_positive_definite(result.covariance));
  // Depth variance: (f B / d^2)^2 sigma_d^2.
  const double depth_sigma = 400.0 * 0.1 / (d * d) * 0.5;
  EXPECT_NEAR(result.covariance(2, 2), depth_sigma * depth_sigma, 1e-12);
}

// Pixel noise drawn with the stated sigmas gives 3D errors whose Mahalanobis distances under
// C follow chi-square with 3 degrees of freedom (for small disparity noise relative to d).
TEST(Triangulation, MonteCarloErrorsMatchCovariance) {
  const StereoCalibration camera = paper_camera();
  const StereoNoise noise{2.0, 2.0, 0.2};
  const double x = 250.0;
  const double y = 300.0;
  const double d = 40.0;
  const Eigen::Vector3d truth = triangulate_point(camera, x, y, d);
  const Eigen::Matrix3d covariance = triangulate(camera, noise, x, y, d).covariance;
  double sum = 0.0;
  const int samples = 4000;
  core::RandomStream random(7, core::StreamId{0, 0, 0});
  for (int i = 0; i < samples; ++i) {
    const double nx = x + noise.sigma_u_px * random.gaussian();
    const double ny = y + noise.sigma_v_px * random.gaussian();
    const double nd = d + noise.sigma_d_px * random.gaussian();
    sum += core::mahalanobis_squared(triangulate_point(camera, nx, ny, nd) - truth, covariance);
  }
  EXPECT_NEAR(sum / samples, 3.0, 0.2);
}

}  // namespace
}  // namespace stereoscout::vision
