#include "stereoscout/slam/wall_line.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include "stereoscout/core/geometry.hpp"

namespace stereoscout::slam {
namespace {

using Column = core::DepthScanColumn;

// A piece of a run: columns [first, last], both obstacle columns.
struct Piece {
  std::size_t first = 0;
  std::size_t last = 0;
};

// Pieces waiting to be split or fitted; a run of 640 columns splits into far fewer.
constexpr std::size_t kMaxPieces = 64;
// A piece is split while a point lies more than this many times max_rms_m off its chord.
constexpr double kSplitFactor = 3.0;

Eigen::Vector2d point_of(const Column& column) { return {column.x_robot_m, column.y_robot_m}; }

bool usable(const core::DepthScan& scan, std::size_t i, double max_range_m) {
  const Column& c = scan.columns[i];
  return c.kind == Column::Kind::obstacle && (point_of(c) - scan.origin_robot).norm() <= max_range_m;
}

// The column of `piece` farthest from its chord, and that distance.
std::size_t farthest_from_chord(const core::DepthScan& scan, const Piece& piece, double& distance) {
  const Eigen::Vector2d a = point_of(scan.columns[piece.first]);
  const Eigen::Vector2d chord = point_of(scan.columns[piece.last]) - a;
  const double length = chord.norm();
  distance = 0.0;
  std::size_t farthest = piece.first;
  for (std::size_t i = piece.first + 1; i < piece.last; ++i) {
    const Eigen::Vector2d to_point = point_of(scan.columns[i]) - a;
    const double d = length > 0.0 ? std::abs(chord.x() * to_point.y() - chord.y() * to_point.x()) / length
                                   : to_point.norm();
    if (d > distance) {
      distance = d;
      farthest = i;
    }
  }
  return farthest;
}

// Total least squares over the piece's points; false when it does not pass as a wall.
bool fit_piece(const core::DepthScan& scan, const Piece& piece, const WallLineParams& params, WallLine& line) {
  const int count = static_cast<int>(piece.last - piece.first + 1);
  if (count < params.min_points) return false;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (std::size_t i = piece.first; i <= piece.last; ++i) mean += point_of(scan.columns[i]);
  mean /= count;
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (std::size_t i = piece.first; i <= piece.last; ++i) {
    const Eigen::Vector2d d = point_of(scan.columns[i]) - mean;
    scatter += d * d.transpose();
  }
  const double direction = core::principal_axis_angle(scatter(0, 0), scatter(0, 1), scatter(1, 1));
  const Eigen::Vector2d along_line(std::cos(direction), std::sin(direction));
  const Eigen::Vector2d across_line(-along_line.y(), along_line.x());
  double along_min = 0.0;
  double along_max = 0.0;
  double across_squared = 0.0;
  for (std::size_t i = piece.first; i <= piece.last; ++i) {
    const Eigen::Vector2d d = point_of(scan.columns[i]) - mean;
    const double along = d.dot(along_line);
    const double across = d.dot(across_line);
    along_min = std::min(along_min, along);
    along_max = std::max(along_max, along);
    across_squared += across * across;
  }
  const double rms = std::sqrt(across_squared / count);
  const double length = along_max - along_min;
  if (rms > params.max_rms_m || length < params.min_length_m) return false;
  line.direction_rad = direction < 0.0 ? direction + core::kPi : direction;
  line.length_m = length;
  line.rms_m = rms;
  line.points = count;
  return true;
}

// Splits one run into pieces and keeps the longest wall among them in `best`.
void fit_run(const core::DepthScan& scan, Piece run, const WallLineParams& params, WallLine& best, bool& found) {
  std::array<Piece, kMaxPieces> pending{};
  std::size_t waiting = 0;
  pending[waiting++] = run;
  while (waiting > 0) {
    const Piece piece = pending[--waiting];
    if (static_cast<int>(piece.last - piece.first + 1) < params.min_points) continue;
    double distance = 0.0;
    const std::size_t split = farthest_from_chord(scan, piece, distance);
    if (distance > kSplitFactor * params.max_rms_m && waiting + 2 <= kMaxPieces) {
      pending[waiting++] = Piece{piece.first, split};
      pending[waiting++] = Piece{split, piece.last};
      continue;
    }
    WallLine line;
    if (fit_piece(scan, piece, params, line) && (!found || line.length_m > best.length_m)) {
      best = line;
      found = true;
    }
  }
}

}  // namespace

WallLineParams wall_line_params_from_config(const core::FilterConfig& config) {
  WallLineParams params;
  params.min_length_m = config.manhattan_wall_min_length_m;
  params.max_range_m = config.manhattan_wall_max_range_m;
  params.max_rms_m = config.manhattan_wall_max_rms_m;
  params.max_gap_m = config.manhattan_wall_max_gap_m;
  return params;
}

bool fit_wall_line(const core::DepthScan& scan, const WallLineParams& params, WallLine& line) {
  bool found = false;
  const std::size_t n = scan.columns.size();
  std::size_t i = 0;
  while (i < n) {
    if (!usable(scan, i, params.max_range_m)) {
      ++i;
      continue;
    }
    Piece run{i, i};
    while (run.last + 1 < n && usable(scan, run.last + 1, params.max_range_m) &&
           (point_of(scan.columns[run.last + 1]) - point_of(scan.columns[run.last])).norm() <= params.max_gap_m) {
      ++run.last;
    }
    fit_run(scan, run, params, line, found);
    i = run.last + 1;
  }
  return found;
}

}  // namespace stereoscout::slam
