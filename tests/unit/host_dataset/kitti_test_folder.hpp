#pragma once
// A small synthetic KITTI odometry folder written by a test (removed with it).
#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "stereoscout/host_dataset/kitti_sequence.hpp"

namespace stereoscout::host_dataset::test {

inline const char* kCalibration =
    "P0: 700.0 0.0 300.0 0.0 0.0 700.0 100.0 0.0 0.0 0.0 1.0 0.0\n"
    "P1: 700.0 0.0 300.0 -350.0 0.0 700.0 100.0 0.0 0.0 0.0 1.0 0.0\n"
    "P2: 1 2 3\n";  // other lines (colour cameras, Tr) are not read

class KittiTestFolder {
 public:
  explicit KittiTestFolder(int frames, int width = 64, int height = 48) {
    char pattern[] = "/tmp/kitti_test_XXXXXX";
    path_ = ::mkdtemp(pattern);
    ::mkdir((path_ + "/image_0").c_str(), 0755);
    ::mkdir((path_ + "/image_1").c_str(), 0755);
    write("calib.txt", kCalibration);
    std::string times;
    std::string poses;
    for (int k = 0; k < frames; ++k) {
      times += std::to_string(0.1 * k) + "\n";
      // Straight ahead along the camera's z axis, 1 m per frame.
      poses += "1 0 0 0 0 1 0 0 0 0 1 " + std::to_string(k) + "\n";
      const cv::Mat image(height, width, CV_8UC1, cv::Scalar(static_cast<double>(10 * k)));
      cv::imwrite(kitti_image_path(path_, 0, static_cast<std::size_t>(k)), image);
      cv::imwrite(kitti_image_path(path_, 1, static_cast<std::size_t>(k)), image);
    }
    write("times.txt", times);
    write("poses.txt", poses);
  }
  ~KittiTestFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  KittiTestFolder(const KittiTestFolder&) = delete;
  KittiTestFolder& operator=(const KittiTestFolder&) = delete;

  void write(const std::string& name, const std::string& text) const {
    std::ofstream(path_ + "/" + name, std::ios::binary) << text;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace stereoscout::host_dataset::test
