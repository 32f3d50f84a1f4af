#include "stereoscout/vision/calibration.hpp"

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::vision {

StereoCalibration calibration_from_config(const core::CameraConfig& camera) {
  StereoCalibration calibration;
  calibration.focal_px = camera.focal_px;
  calibration.principal_x_px = camera.principal_x_px;
  calibration.principal_y_px = camera.principal_y_px;
  calibration.baseline_m = camera.baseline_m;
  calibration.width_px = camera.width_px;
  calibration.height_px = camera.height_px;
  return calibration;
}

StereoNoise noise_from_config(const core::VisionConfig& vision) {
  return {vision.sigma_u_px, vision.sigma_v_px, vision.sigma_d_px};
}

Eigen::Vector3d triangulate_point(const StereoCalibration& calibration, double x_right_px,
                                  double y_right_px, double disparity_px) {
  const double u = x_right_px - calibration.principal_x_px;
  const double v = y_right_px - calibration.principal_y_px;
  // X = u Z / f = u B / d (and likewise Y), Z = f B / d.
  const double scale = calibration.baseline_m / disparity_px;
  return {u * scale, v * scale, calibration.focal_px * scale};
}

StereoPoint triangulate(const StereoCalibration& calibration, const StereoNoise& noise,
                        double x_right_px, double y_right_px, double disparity_px) {
  StereoPoint result;
  result.point_camera = triangulate_point(calibration, x_right_px, y_right_px, disparity_px);
  const Eigen::Matrix3d jacobian = core::stereo_triangulation_jacobian(
      calibration.focal_px, calibration.baseline_m, x_right_px - calibration.principal_x_px,
      y_right_px - calibration.principal_y_px, disparity_px);
  const Eigen::Vector3d variances(noise.sigma_u_px * noise.sigma_u_px, noise.sigma_v_px * noise.sigma_v_px,
                                  noise.sigma_d_px * noise.sigma_d_px);
  result.covariance = jacobian * variances.asDiagonal() * jacobian.transpose();
  return result;
}

}  // namespace stereoscout::vision
