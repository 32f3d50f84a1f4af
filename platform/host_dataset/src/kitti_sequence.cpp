#include "stereoscout/host_dataset/kitti_sequence.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

namespace stereoscout::host_dataset {
namespace {

std::string located(const std::string& name, std::size_t line, const std::string& what) {
  return name + ":" + std::to_string(line) + ": " + what;
}

// All numbers of `fields`; false when a field is not a finite number.
bool read_numbers(std::istringstream& fields, std::vector<double>& numbers) {
  numbers.clear();
  std::string field;
  while (fields >> field) {
    char* end = nullptr;
    const double value = std::strtod(field.c_str(), &end);
    if (end == field.c_str() || *end != '\0' || !std::isfinite(value)) return false;
    numbers.push_back(value);
  }
  return true;
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

// Calls use(line, numbers) for every non-blank line of `text` holding exactly `count`
// numbers; a line that does not sets `error` to "<name>:<line>: <what>" and stops.
template <class Use>
bool parse_number_lines(const std::string& text, const std::string& name, std::size_t count, const char* what,
                        std::string& error, Use&& use) {
  std::istringstream lines(text);
  std::string line;
  std::vector<double> numbers;
  for (std::size_t number = 1; std::getline(lines, line); ++number) {
    if (blank(line)) continue;
    std::istringstream fields(line);
    if (!read_numbers(fields, numbers) || numbers.size() != count) {
      error = located(name, number, what);
      return false;
    }
    if (!use(number, numbers)) return false;
  }
  return true;
}

bool read_file(const std::string& path, std::string& text, std::string& error) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    error = path + ": cannot open";
    return false;
  }
  std::ostringstream content;
  content << file.rdbuf();
  text = content.str();
  return true;
}

}  // namespace

bool parse_kitti_calibration(const std::string& text, const std::string& name, KittiCalibration& calibration,
                             std::string& error) {
  std::istringstream lines(text);
  std::string line;
  std::vector<double> p0;
  std::vector<double> p1;
  std::vector<double> numbers;
  for (std::size_t number = 1; std::getline(lines, line); ++number) {
    std::istringstream fields(line);
    std::string key;
    fields >> key;
    if (key != "P0:" && key != "P1:") continue;  // P2, P3, Tr: not needed for grey stereo
    if (!read_numbers(fields, numbers) || numbers.size() != 12) {
      error = located(name, number, key + " needs 12 numbers (a 3x4 projection matrix, row-major)");
      return false;
    }
    (key == "P0:" ? p0 : p1) = numbers;
  }
  if (p0.empty() || p1.empty()) {
    error = name + ": " + (p0.empty() ? "no P0: line" : "no P1: line");
    return false;
  }
  calibration.focal_px = p0[0];
  calibration.principal_x_px = p0[2];
  calibration.principal_y_px = p0[6];
  // P1 = K [I | -B e_x] for the right camera a baseline B to the right: P1[0][3] = -f B.
  calibration.baseline_m = p1[0] > 0.0 ? -p1[3] / p1[0] : 0.0;
  if (calibration.focal_px <= 0.0 || calibration.baseline_m <= 0.0) {
    error = name + ": P0/P1 give focal " + std::to_string(calibration.focal_px) + " px and baseline " +
            std::to_string(calibration.baseline_m) + " m; both must be > 0 (image_1 the right camera)";
    return false;
  }
  return true;
}

bool parse_kitti_times(const std::string& text, const std::string& name, std::vector<double>& times_s,
                       std::string& error) {
  times_s.clear();
  return parse_number_lines(text, name, 1, "expected one time in seconds", error,
                            [&](std::size_t line, const std::vector<double>& numbers) {
                              // Strictly increasing: a frame's time names its trajectory node in the outputs.
                              if (!times_s.empty() && numbers[0] <= times_s.back()) {
                                error = located(name, line, "time does not increase");
                                return false;
                              }
                              times_s.push_back(numbers[0]);
                              return true;
                            });
}

bool parse_kitti_poses(const std::string& text, const std::string& name, std::vector<Eigen::Isometry3d>& poses,
                       std::string& error) {
  poses.clear();
  return parse_number_lines(text, name, 12, "expected 12 numbers (3x4 [R|t], row-major)", error,
                            [&](std::size_t /*line*/, const std::vector<double>& numbers) {
                              Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
                              for (int row = 0; row < 3; ++row) {
                                for (int col = 0; col < 4; ++col) {
                                  pose.matrix()(row, col) = numbers[static_cast<std::size_t>(row * 4 + col)];
                                }
                              }
                              poses.push_back(pose);
                              return true;
                            });
}

std::string kitti_image_path(const std::string& folder, int camera, std::size_t frame) {
  char name[48];
  std::snprintf(name, sizeof name, "/image_%d/%06zu.png", camera, frame);
  return folder + name;
}

bool load_kitti_sequence(const std::string& folder, std::size_t max_frames, KittiSequence& sequence,
                         std::string& error) {
  sequence = KittiSequence{};
  sequence.folder = folder;
  std::string text;
  const std::string calib = folder + "/calib.txt";
  if (!read_file(calib, text, error) || !parse_kitti_calibration(text, calib, sequence.calibration, error)) {
    return false;
  }
  const std::string times = folder + "/times.txt";
  if (!read_file(times, text, error) || !parse_kitti_times(text, times, sequence.times_s, error)) return false;
  if (sequence.times_s.empty()) {
    error = times + ": no frames";
    return false;
  }
  if (max_frames > 0 && sequence.times_s.size() > max_frames) sequence.times_s.resize(max_frames);
  const std::string poses = folder + "/poses.txt";
  if (std::ifstream(poses).good()) {  // the test sequences 11-21 have no ground truth
    if (!read_file(poses, text, error) || !parse_kitti_poses(text, poses, sequence.world_from_cam0, error)) {
      return false;
    }
    if (sequence.world_from_cam0.size() < sequence.frames()) {
      error = poses + ": " + std::to_string(sequence.world_from_cam0.size()) + " poses for " +
              std::to_string(sequence.frames()) + " frames of times.txt";
      return false;
    }
    sequence.world_from_cam0.resize(sequence.frames());
  }
  for (int camera = 0; camera < 2; ++camera) {
    const std::string first = kitti_image_path(folder, camera, 0);
    const cv::Mat image = cv::imread(first, cv::IMREAD_GRAYSCALE);
    if (image.empty()) {
      error = first + ": missing or not an image";
      return false;
    }
    if (camera == 1 && (image.cols != sequence.calibration.width_px || image.rows != sequence.calibration.height_px)) {
      error = first + ": size differs from image_0";
      return false;
    }
    sequence.calibration.width_px = image.cols;
    sequence.calibration.height_px = image.rows;
  }
  return true;
}

core::Pose2 ground_pose_from_camera(const Eigen::Isometry3d& world_from_camera) {
  const Eigen::Vector3d position = world_from_camera.translation();
  const Eigen::Vector3d forward = world_from_camera.linear().col(2);  // the optical axis in the world
  return core::Pose2{position.z(), -position.x(), std::atan2(-forward.x(), forward.z())};
}

Eigen::Isometry3d right_camera_from_left(const Eigen::Isometry3d& world_from_cam0, double baseline_m) {
  Eigen::Isometry3d world_from_cam1 = world_from_cam0;
  world_from_cam1.translation() = world_from_cam0 * Eigen::Vector3d(baseline_m, 0.0, 0.0);
  return world_from_cam1;
}

std::vector<core::Pose2> ground_truth_robot_poses(const KittiSequence& sequence) {
  std::vector<core::Pose2> poses;
  poses.reserve(sequence.world_from_cam0.size());
  // Relative to the right camera at frame 0, so the robot starts at the origin facing +x.
  const Eigen::Isometry3d cam1_origin_inverse =
      right_camera_from_left(Eigen::Isometry3d::Identity(), sequence.calibration.baseline_m).inverse();
  for (const Eigen::Isometry3d& pose : sequence.world_from_cam0) {
    poses.push_back(ground_pose_from_camera(
        cam1_origin_inverse * right_camera_from_left(pose, sequence.calibration.baseline_m)));
  }
  return poses;
}

}  // namespace stereoscout::host_dataset
