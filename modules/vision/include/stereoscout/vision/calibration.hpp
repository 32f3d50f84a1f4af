#pragma once
// The rectified stereo head as the vision front end sees it, and stereo triangulation with
// its first-order covariance (paper section IV, eq. 3 and 4).
//
// The RIGHT image is the reference: a key at pixel (x_r, y_r) of the right image with
// disparity d = x_left - x_right > 0 lies at
//   Z = f B / d,  X = u Z / f,  Y = v Z / f,   u = x_r - c_x,  v = y_r - c_y
// in the right camera's optical frame (x right, y down, z forward).

#include <Eigen/Core>

#include "stereoscout/core/config/camera.hpp"
#include "stereoscout/core/config/vision.hpp"

namespace stereoscout::vision {

// A plain struct so a dataset (KITTI calib.txt, Middlebury) can supply its own calibration.
struct StereoCalibration {
  double focal_px = 400.0;
  double principal_x_px = 319.5;
  double principal_y_px = 239.5;
  double baseline_m = 0.10;
  int width_px = 640;
  int height_px = 480;
};

StereoCalibration calibration_from_config(const core::CameraConfig& camera);

// Pixel noise of a stereo measurement: S = diag(sigma_u^2, sigma_v^2, sigma_d^2).
struct StereoNoise {
  double sigma_u_px = 10.0;
  double sigma_v_px = 10.0;
  double sigma_d_px = 0.5;
};

StereoNoise noise_from_config(const core::VisionConfig& vision);

struct StereoPoint {
  Eigen::Vector3d point_camera = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
};

// Eq. 3 for a right-image pixel and disparity (> 0), and C = J S J^T with J = d(X,Y,Z)/d(u,v,d).
StereoPoint triangulate(const StereoCalibration& calibration, const StereoNoise& noise,
                        double x_right_px, double y_right_px, double disparity_px);

// Eq. 3 without covariance, for dense disparity maps.
Eigen::Vector3d triangulate_point(const StereoCalibration& calibration, double x_right_px,
                                  double y_right_px, double disparity_px);

}  // namespace stereoscout::vision
