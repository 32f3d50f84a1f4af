// stereoscout landmark-slam: the RBPF landmark filter on one robot of a UTIAS MRCLAM dataset.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <sys/stat.h>

#include "arguments.hpp"
#include "commands.hpp"
#include "mrclam.hpp"
#include "stereoscout/core/system_config.hpp"

namespace stereoscout::cli {
namespace {

bool write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    std::fprintf(stderr, "stereoscout landmark-slam: cannot write %s\n", path.c_str());
    return false;
  }
  return true;
}

std::string json_number(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", value);
  return text;
}

std::string json_residuals(const mrclam::MapScore& score) {
  std::ostringstream out;
  out << "{";
  for (std::size_t i = 0; i < score.residuals_m.size(); ++i) {
    out << (i == 0 ? "" : ", ") << "\"" << score.subjects[i] << "\": " << json_number(score.residuals_m[i]);
  }
  out << "}";
  return out.str();
}

std::string report_json(const mrclam::Dataset& dataset, int robot, const mrclam::RunOptions& options,
                        const mrclam::RunResult& r, double wall_time_s) {
  std::ostringstream out;
  out << "{\n"
      << "  \"robot\": " << robot << ",\n"
      << "  \"particles\": " << options.filter.particles << ",\n"
      << "  \"seed\": " << options.seed << ",\n"
      << "  \"range_sigma_m\": " << json_number(options.range_sigma_m) << ",\n"
      << "  \"bearing_sigma_rad\": " << json_number(options.bearing_sigma_rad) << ",\n"
      << "  \"motion_noise\": [" << json_number(options.noise_translation_per_m) << ", "
      << json_number(options.noise_rotation_per_rad) << ", " << json_number(options.noise_rotation_per_m) << ", "
      << json_number(options.noise_translation_per_rad) << "],\n"
      << "  \"landmark_truth_file\": \"" << dataset.landmark_truth_file << "\",\n"
      << "  \"landmark_rmse_m\": " << json_number(r.filter_map.rmse_m) << ",\n"
      << "  \"landmarks_mapped\": " << r.filter_map.mapped << ",\n"
      << "  \"landmark_residuals_m\": " << json_residuals(r.filter_map) << ",\n"
      << "  \"deadreckoning_landmark_rmse_m\": " << json_number(r.dead_reckoning_map.rmse_m) << ",\n"
      << "  \"deadreckoning_landmarks_mapped\": " << r.dead_reckoning_map.mapped << ",\n"
      << "  \"deadreckoning_landmark_residuals_m\": " << json_residuals(r.dead_reckoning_map) << ",\n";
  if (r.ate_rmse_m) {
    out << "  \"ate_rmse_m\": " << json_number(*r.ate_rmse_m) << ",\n";
  }
  const auto pose_json = [](const core::Pose2& p) {
    return "[" + json_number(p.x) + ", " + json_number(p.y) + ", " + json_number(p.theta) + "]";
  };
  out << "  \"final_ml_pose\": " << pose_json(r.final_ml_pose) << ",\n"
      << "  \"final_weighted_mean_pose\": " << pose_json(r.final_mean_pose) << ",\n"
      << "  \"updates\": " << r.updates << ",\n"
      << "  \"updates_refused_trajectory_full\": " << r.updates_refused << ",\n"
      << "  \"resamplings\": " << r.resamplings << ",\n"
      << "  \"measurements_used\": " << r.measurements_used << ",\n"
      << "  \"robot_measurements_dropped\": " << r.robot_measurements_dropped << ",\n"
      << "  \"unknown_barcodes_dropped\": " << r.unknown_barcodes_dropped << ",\n"
      << "  \"landmark_changes_refused_pool_full\": " << r.changes_refused_pool_full << ",\n"
      << "  \"landmark_nodes_high_water\": " << r.landmark_nodes_high_water << ",\n"
      << "  \"trajectory_nodes_high_water\": " << r.trajectory_nodes_high_water << ",\n"
      << "  \"filter_time_s\": " << json_number(r.filter_seconds) << ",\n"
      << "  \"wall_time_s\": " << json_number(wall_time_s) << "\n"
      << "}\n";
  return out.str();
}

}  // namespace

int run_landmark_slam(int argc, char** argv) {
  Arguments arguments("landmark-slam",
                      "Runs the RBPF landmark filter on one robot of a UTIAS MRCLAM dataset folder and\n"
                      "scores its landmark map (and a dead-reckoning map) against the true landmarks.");
  arguments.option("mrclam", "DIR", "dataset folder, e.g. ../shared/data/mrclam/Dataset1");
  arguments.option("robot", "R", "robot number (1-5)");
  arguments.option("out", "OUT", "output folder (created)");
  arguments.option("particles", "N", "particles (default: filter.particles of the config)");
  arguments.option("seed", "S", "random seed", "1");
  arguments.option("config", "FILE", "config file", default_config_path());
  const mrclam::RunOptions defaults;
  arguments.option("range-sigma", "M", "range noise standard deviation", core::format_number(defaults.range_sigma_m));
  arguments.option("bearing-sigma", "RAD", "bearing noise standard deviation",
                   core::format_number(defaults.bearing_sigma_rad));
  // Commanded velocities, not encoders: these replace filter.motion_noise_* of the config.
  arguments.option("noise-translation-per-m", "M/M", "proposal: translation noise per metre driven",
                   core::format_number(defaults.noise_translation_per_m));
  arguments.option("noise-rotation-per-rad", "RAD/RAD", "proposal: rotation noise per radian turned",
                   core::format_number(defaults.noise_rotation_per_rad));
  arguments.option("noise-rotation-per-m", "RAD/M", "proposal: rotation noise per metre driven",
                   core::format_number(defaults.noise_rotation_per_m));
  arguments.option("noise-translation-per-rad", "M/RAD", "proposal: translation noise per radian turned",
                   core::format_number(defaults.noise_translation_per_rad));
  arguments.option("duration", "S", "use only the first S seconds of the log (0: all)", "0");
  if (!arguments.parse(argc, argv)) {
    return arguments.exit_code();
  }
  for (const char* required : {"mrclam", "robot", "out"}) {
    if (!arguments.has(required)) {
      std::fprintf(stderr, "stereoscout landmark-slam: --%s is required (see --help)\n", required);
      return 2;
    }
  }
  const auto wall_start = std::chrono::steady_clock::now();
  const core::SystemConfigLoad load = core::load_system_config(arguments.get("config"));
  if (!load.ok()) {
    std::fprintf(stderr, "stereoscout landmark-slam: config problems:\n%s", load.error_text().c_str());
    return 1;
  }
  long long robot = 0;
  long long seed = 1;
  long long particles = load.config.filter.particles;
  mrclam::RunOptions options;
  if (!arguments.get_int("robot", robot) || !arguments.get_int("seed", seed) ||
      (arguments.has("particles") && !arguments.get_int("particles", particles)) ||
      !arguments.get_double("range-sigma", options.range_sigma_m) ||
      !arguments.get_double("bearing-sigma", options.bearing_sigma_rad) ||
      !arguments.get_double("duration", options.duration_s) ||
      !arguments.get_double("noise-translation-per-m", options.noise_translation_per_m) ||
      !arguments.get_double("noise-rotation-per-rad", options.noise_rotation_per_rad) ||
      !arguments.get_double("noise-rotation-per-m", options.noise_rotation_per_m) ||
      !arguments.get_double("noise-translation-per-rad", options.noise_translation_per_rad)) {
    return 2;
  }
  if (robot < 1 || particles < 1 || particles > 1000000 || seed < 0 || options.range_sigma_m <= 0.0 ||
      options.bearing_sigma_rad <= 0.0 || options.noise_translation_per_m < 0.0 || options.noise_rotation_per_rad < 0.0 ||
      options.noise_rotation_per_m < 0.0 || options.noise_translation_per_rad < 0.0) {
    std::fprintf(stderr,
                 "stereoscout landmark-slam: --robot and --particles must be >= 1, sigmas > 0, noise terms >= 0\n");
    return 2;
  }
  options.filter = load.config.filter;
  options.filter.particles = static_cast<int>(particles);
  if (options.filter.particle_capacity < options.filter.particles) {
    options.filter.particle_capacity = options.filter.particles;
  }
  options.seed = static_cast<std::uint64_t>(seed);

  mrclam::Dataset dataset;
  std::string error;
  if (!mrclam::load_dataset(arguments.get("mrclam"), static_cast<int>(robot), dataset, error)) {
    std::fprintf(stderr, "stereoscout landmark-slam: %s\n", error.c_str());
    return 1;
  }
  const std::string out = arguments.get("out");
  ::mkdir(out.c_str(), 0755);
  const mrclam::RunResult result = mrclam::run_landmark_slam(dataset, options);
  const double wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const bool written = write_text(out + "/trajectory.tum", result.trajectory_tum) &&
                       write_text(out + "/odometry.tum", result.odometry_tum) &&
                       write_text(out + "/landmarks.ply", result.landmarks_ply) &&
                       write_text(out + "/report.json", report_json(dataset, static_cast<int>(robot), options, result,
                                                                    wall_time_s));
  if (!written) {
    return 1;
  }
  std::printf("robot %lld: landmark RMSE %.3f m over %zu landmarks (dead reckoning %.3f m over %zu), %" PRIu64
              " updates, %.1f s\n",
              robot, result.filter_map.rmse_m, result.filter_map.mapped, result.dead_reckoning_map.rmse_m,
              result.dead_reckoning_map.mapped, result.updates, wall_time_s);
  return 0;
}

}  // namespace stereoscout::cli
