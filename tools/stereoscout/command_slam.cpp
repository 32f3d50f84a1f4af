// stereoscout slam --kitti: the vision front end and the RBPF on a real stereo sequence in the
// KITTI odometry layout, scored against its ground truth (docs/results.md, "Real stereo: KITTI").
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/stat.h>

#include "arguments.hpp"
#include "commands.hpp"
#include "kitti_run.hpp"
#include "stereoscout/core/system_config.hpp"

namespace stereoscout::cli {
namespace {

constexpr const char* kName = "stereoscout slam";

bool write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) {
    std::fprintf(stderr, "%s: cannot write %s\n", kName, path.c_str());
    return false;
  }
  return true;
}

std::string json_number(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", value);
  return text;
}

// "T,R,RM,SCALE,DRIFT" in the units of config dataset.odometry, or "none".
bool parse_odometry_noise(const std::string& text, core::OdometryNoiseConfig& noise) {
  if (text == "none") {
    noise = core::OdometryNoiseConfig{};
    return true;
  }
  double values[5];
  std::istringstream fields(text);
  std::string field;
  int count = 0;
  while (std::getline(fields, field, ',')) {
    char* end = nullptr;
    if (count == 5) return false;
    values[count] = std::strtod(field.c_str(), &end);
    if (end == field.c_str() || *end != '\0') return false;
    ++count;
  }
  if (count != 5) return false;
  noise = core::OdometryNoiseConfig{values[0], values[1], values[2], values[3], values[4]};
  return noise.translation_sigma_m_per_sqrt_m >= 0.0 && noise.rotation_sigma_rad_per_sqrt_rad >= 0.0 &&
         noise.rotation_sigma_rad_per_sqrt_m >= 0.0 && noise.scale_error > -0.5 && noise.scale_error < 0.5;
}

void append_score(std::ostringstream& out, const char* prefix, const kitti::TrajectoryScore& score) {
  out << "  \"" << prefix << "ate_rmse_m\": " << json_number(score.ate_rmse_m) << ",\n"
      << "  \"" << prefix << "rpe_m_per_m\": " << json_number(score.rpe_per_m) << ",\n";
}

std::string report_json(const host_dataset::KittiSequence& sequence, const kitti::RunOptions& options,
                        const kitti::RunResult& r, double wall_time_s) {
  const core::OdometryNoiseConfig& noise = options.dataset.odometry;
  std::ostringstream out;
  out << "{\n"
      << "  \"sequence\": \"" << sequence.folder << "\",\n"
      << "  \"particles\": " << options.filter.particles << ",\n"
      << "  \"seed\": " << options.seed << ",\n"
      << "  \"odometry_noise\": [" << json_number(noise.translation_sigma_m_per_sqrt_m) << ", "
      << json_number(noise.rotation_sigma_rad_per_sqrt_rad) << ", " << json_number(noise.rotation_sigma_rad_per_sqrt_m)
      << ", " << json_number(noise.scale_error) << ", " << json_number(noise.drift_deg_per_m) << "],\n"
      << "  \"frames\": " << r.frames << ",\n"
      << "  \"frames_skipped\": " << r.frames_skipped << ",\n"
      << "  \"frames_without_features\": " << r.frames_without_features << ",\n";
  append_score(out, "", *r.filter_score);
  append_score(out, "odometry_", *r.odometry_score);
  out << "  \"rpe_segment_m\": " << json_number(options.rpe_segment_m) << ",\n"
      << "  \"landmarks\": " << r.landmarks << ",\n"
      << "  \"identities\": " << r.identities << ",\n"
      << "  \"stereo_matches\": " << r.stereo_matches << ",\n"
      << "  \"observations\": " << r.observations << ",\n"
      << "  \"observations_matched_share\": " << json_number(r.matched_share()) << ",\n"
      << "  \"reobservations\": " << r.reobservations << ",\n"
      << "  \"reobservation_consistency\": " << json_number(r.reobservation_consistency()) << ",\n"
      << "  \"resamplings\": " << r.resamplings << ",\n"
      << "  \"updates_refused_trajectory_full\": " << r.updates_refused << ",\n"
      << "  \"landmark_changes_refused_pool_full\": " << r.changes_refused_pool_full << ",\n"
      << "  \"landmark_nodes_high_water\": " << r.landmark_nodes_high_water << ",\n"
      << "  \"time_sift_s\": " << json_number(r.times.sift_s) << ",\n"
      << "  \"time_stereo_matching_s\": " << json_number(r.times.stereo_matching_s) << ",\n"
      << "  \"time_index_lookup_s\": " << json_number(r.times.index_lookup_s) << ",\n"
      << "  \"time_filter_update_s\": " << json_number(r.times.filter_update_s) << ",\n"
      << "  \"wall_time_s\": " << json_number(wall_time_s) << "\n"
      << "}\n";
  return out.str();
}

void declare(Arguments& arguments) {
  arguments.option("kitti", "DIR", "KITTI odometry folder (image_0/, image_1/, calib.txt, times.txt, poses.txt)");
  arguments.option("out", "OUT", "output folder (created)");
  arguments.option("particles", "N", "particles (default: filter.particles of the config)");
  arguments.option("seed", "S", "random seed (odometry noise and filter)", "1");
  arguments.option("odometry-noise", "T,R,RM,SCALE,DRIFT",
                   "odometry noise replacing config dataset.odometry: m/sqrt(m), rad/sqrt(rad), rad/sqrt(m), "
                   "scale error, deg/m; or 'none'");
  arguments.option("frames", "N", "use only the first N frames (0: all)", "0");
  arguments.option("rpe-segment", "M", "path length of the relative pose error's segments", "10");
  arguments.option("config", "FILE", "config file", default_config_path());
}

// Reads the options into `options`; false (message printed) on a bad value.
bool read_options(const Arguments& arguments, const core::SystemConfig& config, kitti::RunOptions& options,
                  long long& frames) {
  long long seed = 1;
  long long particles = config.filter.particles;
  if (!arguments.get_int("seed", seed) || !arguments.get_int("frames", frames) ||
      (arguments.has("particles") && !arguments.get_int("particles", particles)) ||
      !arguments.get_double("rpe-segment", options.rpe_segment_m)) {
    return false;
  }
  if (particles < 1 || particles > 1000000 || seed < 0 || frames < 0 || options.rpe_segment_m <= 0.0) {
    std::fprintf(stderr, "%s: --particles must be 1..1000000, --seed and --frames >= 0, --rpe-segment > 0\n", kName);
    return false;
  }
  options.vision = config.vision;
  options.filter = config.filter;
  options.dataset = config.dataset;
  options.filter.particles = static_cast<int>(particles);
  if (options.filter.particle_capacity < options.filter.particles) options.filter.particle_capacity = options.filter.particles;
  options.seed = static_cast<std::uint64_t>(seed);
  if (arguments.has("odometry-noise") && !parse_odometry_noise(arguments.get("odometry-noise"), options.dataset.odometry)) {
    std::fprintf(stderr, "%s: --odometry-noise wants five numbers T,R,RM,SCALE,DRIFT (sigmas >= 0, |SCALE| < 0.5) "
                 "or 'none', got '%s'\n", kName, arguments.get("odometry-noise").c_str());
    return false;
  }
  return true;
}

}  // namespace

int run_slam(int argc, char** argv) {
  Arguments arguments("slam",
                      "Runs the vision front end and the RBPF over a real stereo sequence in the KITTI odometry\n"
                      "layout (every frame an observation update; odometry = ground-truth motion plus seeded noise)\n"
                      "and scores the trajectory against the ground truth.");
  declare(arguments);
  if (!arguments.parse(argc, argv)) return arguments.exit_code();
  for (const char* required : {"kitti", "out"}) {
    if (!arguments.has(required)) {
      std::fprintf(stderr, "%s: --%s is required (see --help)\n", kName, required);
      return 2;
    }
  }
  const auto wall_start = std::chrono::steady_clock::now();
  const core::SystemConfigLoad load = core::load_system_config(arguments.get("config"));
  if (!load.ok()) {
    std::fprintf(stderr, "%s: config problems:\n%s", kName, load.error_text().c_str());
    return 1;
  }
  kitti::RunOptions options;
  long long frames = 0;
  if (!read_options(arguments, load.config, options, frames)) return 2;
  host_dataset::KittiSequence sequence;
  std::string error;
  if (!host_dataset::load_kitti_sequence(arguments.get("kitti"), static_cast<std::size_t>(frames), sequence, error)) {
    std::fprintf(stderr, "%s: %s\n", kName, error.c_str());
    return 1;
  }
  if (!sequence.has_ground_truth()) {
    std::fprintf(stderr, "%s: %s/poses.txt is missing: KITTI has no wheel odometry, it is made from the ground truth\n",
                 kName, sequence.folder.c_str());
    return 1;
  }
  const std::string out = arguments.get("out");
  ::mkdir(out.c_str(), 0755);
  const kitti::RunResult result = kitti::run_kitti_slam(sequence, options);
  for (const std::string& warning : result.warnings) std::fprintf(stderr, "%s: %s\n", kName, warning.c_str());
  const double wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  const bool written = write_text(out + "/trajectory.tum", result.trajectory_tum) &&
                       write_text(out + "/odometry.tum", result.odometry_tum) &&
                       write_text(out + "/groundtruth.tum", result.groundtruth_tum) &&
                       write_text(out + "/landmarks.ply", result.landmarks_ply) &&
                       write_text(out + "/report.json", report_json(sequence, options, result, wall_time_s));
  if (!written) return 1;
  std::printf("%zu frames: ATE %.3f m (odometry %.3f m), RPE %.4f m/m (odometry %.4f m/m), %zu landmarks, "
              "re-observations consistent %.1f %%, %.1f s\n",
              result.frames, result.filter_score->ate_rmse_m, result.odometry_score->ate_rmse_m,
              result.filter_score->rpe_per_m, result.odometry_score->rpe_per_m, result.landmarks,
              100.0 * result.reobservation_consistency(), wall_time_s);
  return 0;
}

}  // namespace stereoscout::cli
