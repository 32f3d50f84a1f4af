#include "map_png.hpp"

#include <algorithm>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace stereoscout::cli {
namespace {

// BGR colours of the three paths, chosen to stay apart from the grey map.
const cv::Scalar kTrajectoryColour(200, 60, 0);
const cv::Scalar kOdometryColour(0, 0, 220);
const cv::Scalar kPlanColour(0, 170, 0);

void draw_path(cv::Mat& image, const occupancy::GridGeometry& geometry, const std::vector<Eigen::Vector2d>& path,
               const cv::Scalar& colour, int thickness) {
  if (path.empty()) return;
  std::vector<cv::Point> pixels;
  pixels.reserve(path.size());
  for (const Eigen::Vector2d& point : path) {
    const double column = (point.x() - geometry.origin_x_m) / geometry.resolution_m;
    const double row = geometry.height_cells - (point.y() - geometry.origin_y_m) / geometry.resolution_m;
    pixels.emplace_back(static_cast<int>(column), static_cast<int>(row));
  }
  if (pixels.size() == 1) {
    cv::circle(image, pixels.front(), thickness, colour, cv::FILLED);
    return;
  }
  cv::polylines(image, pixels, false, colour, thickness, cv::LINE_AA);
}

}  // namespace

std::string write_map_png(const occupancy::RosMap& map, const MapOverlays& overlays, const std::string& png_path) {
  const occupancy::GridGeometry& geometry = map.geometry;
  cv::Mat image(geometry.height_cells, geometry.width_cells, CV_8UC3);
  for (int y = 0; y < geometry.height_cells; ++y) {
    cv::Vec3b* row = image.ptr<cv::Vec3b>(geometry.height_cells - 1 - y);  // top row = highest y
    for (int x = 0; x < geometry.width_cells; ++x) {
      const occupancy::CellState state = map.at(x, y);
      const unsigned char grey = state == occupancy::CellState::occupied ? 0
                                 : state == occupancy::CellState::free   ? 254
                                                                         : 205;
      row[x] = cv::Vec3b(grey, grey, grey);
    }
  }
  // Lines about 3 cm wide on the 1 cm final map, one pixel on the 10 cm grid.
  const int thickness = std::max(1, static_cast<int>(0.03 / geometry.resolution_m));
  draw_path(image, geometry, overlays.raw_odometry, kOdometryColour, thickness);
  draw_path(image, geometry, overlays.estimated_trajectory, kTrajectoryColour, thickness);
  draw_path(image, geometry, overlays.plan, kPlanColour, thickness);
  try {
    if (!cv::imwrite(png_path, image)) return "cannot write " + png_path;
  } catch (const cv::Exception& error) {
    return "cannot write " + png_path + ": " + error.what();
  }
  return {};
}

}  // namespace stereoscout::cli
