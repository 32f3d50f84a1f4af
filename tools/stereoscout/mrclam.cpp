// Reading the MRCLAM files: whitespace-separated numbers, '#' comment lines at the top.
#include "mrclam.hpp"

#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace stereoscout::cli::mrclam {
namespace {

bool file_exists(const std::string& path) { return std::ifstream(path).good(); }

// Calls on_row(numbers) for every data line of `path` with exactly `columns` numbers.
template <class OnRow>
bool read_table(const std::string& path, std::size_t columns, const char* layout, OnRow&& on_row,
                std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = path + ": cannot open (missing file?)";
    return false;
  }
  std::string line;
  std::size_t line_number = 0;
  std::vector<double> numbers;
  while (std::getline(in, line)) {
    ++line_number;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') {
      continue;
    }
    numbers.clear();
    const char* cursor = line.c_str();
    char* end = nullptr;
    while (true) {
      errno = 0;
      const double value = std::strtod(cursor, &end);
      if (end == cursor) {
        break;
      }
      if (errno == ERANGE) {
        numbers.clear();
        break;
      }
      numbers.push_back(value);
      cursor = end;
    }
    const bool only_space = std::string(cursor).find_first_not_of(" \t\r") == std::string::npos;
    if (numbers.size() != columns || !only_space) {
      std::ostringstream message;
      message << path << ":" << line_number << ": expected " << columns << " numbers (" << layout << "), got '"
              << line << "'";
      error = message.str();
      return false;
    }
    if (!on_row(numbers, line_number)) {
      std::ostringstream message;
      message << path << ":" << line_number << ": value out of range in '" << line << "'";
      error = message.str();
      return false;
    }
  }
  if (line_number == 0) {
    error = path + ": empty file";
    return false;
  }
  return true;
}

bool is_whole(double value) { return value == static_cast<double>(static_cast<long long>(value)); }

}  // namespace

bool load_dataset(const std::string& folder, int robot, Dataset& dataset, std::string& error) {
  dataset = Dataset{};
  const std::string prefix = folder + "/Robot" + std::to_string(robot) + "_";
  std::vector<std::pair<int, int>> barcodes;  // subject, barcode
  const bool barcodes_ok = read_table(
      folder + "/Barcodes.dat", 2, "subject, barcode",
      [&](const std::vector<double>& v, std::size_t) {
        if (!is_whole(v[0]) || !is_whole(v[1]) || v[0] < 1 || v[1] < 0 || v[1] > 100000) {
          return false;
        }
        barcodes.emplace_back(static_cast<int>(v[0]), static_cast<int>(v[1]));
        return true;
      },
      error);
  if (!barcodes_ok) {
    return false;
  }
  for (const auto& [subject, barcode] : barcodes) {
    if (static_cast<std::size_t>(barcode) >= dataset.subject_of_barcode.size()) {
      dataset.subject_of_barcode.resize(static_cast<std::size_t>(barcode) + 1, 0);
    }
    dataset.subject_of_barcode[static_cast<std::size_t>(barcode)] = subject;
  }
  const std::string corrected = folder + "/Landmark_Groundtruth.corrected.dat";
  dataset.landmark_truth_file = file_exists(corrected) ? corrected : folder + "/Landmark_Groundtruth.dat";
  const bool truth_ok = read_table(
      dataset.landmark_truth_file, 5, "subject, x, y, x std-dev, y std-dev",
      [&](const std::vector<double>& v, std::size_t) {
        if (!is_whole(v[0]) || v[0] < kFirstLandmarkSubject) {
          return false;
        }
        dataset.landmarks.push_back({static_cast<int>(v[0]), v[1], v[2]});
        return true;
      },
      error);
  if (!truth_ok) {
    return false;
  }
  const bool odometry_ok = read_table(
      prefix + "Odometry.dat", 3, "time, forward velocity, angular velocity",
      [&](const std::vector<double>& v, std::size_t) {
        dataset.odometry.push_back({v[0], v[1], v[2]});
        return true;
      },
      error);
  if (!odometry_ok) {
    return false;
  }
  if (dataset.odometry.empty()) {
    error = prefix + "Odometry.dat: no odometry rows";
    return false;
  }
  const bool measurements_ok = read_table(
      prefix + "Measurement.dat", 4, "time, barcode, range, bearing",
      [&](const std::vector<double>& v, std::size_t) {
        if (!is_whole(v[1]) || v[1] < 0 || v[2] < 0) {
          return false;
        }
        dataset.measurements.push_back({v[0], static_cast<int>(v[1]), v[2], v[3]});
        return true;
      },
      error);
  if (!measurements_ok) {
    return false;
  }
  const std::string groundtruth = prefix + "Groundtruth.dat";
  if (file_exists(groundtruth)) {
    return read_table(
        groundtruth, 4, "time, x, y, orientation",
        [&](const std::vector<double>& v, std::size_t) {
          dataset.groundtruth.push_back({v[0], core::Pose2{v[1], v[2], core::wrap_angle(v[3])}});
          return true;
        },
        error);
  }
  return true;
}

}  // namespace stereoscout::cli::mrclam
