#include "run_setup.hpp"

#include <cstdio>
#include <filesystem>

#include "commands.hpp"
#include "stereoscout/host_sim/renderer.hpp"

namespace stereoscout::cli {
namespace {

bool apply_overrides(const Arguments& arguments, const char* command, core::SystemConfig& config) {
  long long seed = config.run.seed;
  long long particles = config.filter.particles;
  double max_time = config.run.max_time_s;
  if ((arguments.has("seed") && !arguments.get_int("seed", seed)) ||
      (arguments.has("particles") && !arguments.get_int("particles", particles)) ||
      (arguments.has("max-time") && !arguments.get_double("max-time", max_time))) {
    return false;
  }
  if (seed < 0 || seed > 2147483647 || particles < 1 || particles > 1000000 || !(max_time > 0.0)) {
    std::fprintf(stderr, "%s: --seed must be 0..2147483647, --particles 1..1000000, --max-time > 0\n", command);
    return false;
  }
  config.run.seed = seed;
  config.run.max_time_s = max_time;
  config.filter.particles = static_cast<int>(particles);
  if (config.filter.particle_capacity < config.filter.particles) config.filter.particle_capacity = config.filter.particles;
  if (arguments.has("localization")) config.run.localization = arguments.get("localization");
  if (arguments.has("world")) config.run.world = arguments.get("world");
  return true;
}

}  // namespace

bool stack_options_from(const core::SystemConfig& config, const char* command, stack::StackOptions& options) {
  if (!stack::parse_localization(config.run.localization, options.localization)) {
    std::fprintf(stderr, "%s: localization '%s': expected rbpf, groundtruth or odometry\n", command,
                 config.run.localization.c_str());
    return false;
  }
  options.max_time_s = config.run.max_time_s;
  return true;
}

bool load_run_setup(const Arguments& arguments, const char* command, RunSetup& setup) {
  const core::SystemConfigLoad load = core::load_system_config(arguments.get("config"));
  if (!load.ok()) {
    std::fprintf(stderr, "%s: config problem(s):\n%s", command, load.error_text().c_str());
    return false;
  }
  setup.config = load.config;
  if (!apply_overrides(arguments, command, setup.config)) return false;
  const std::string unsupported = host_sim::check_camera_supported(setup.config.camera);
  if (!unsupported.empty()) {
    std::fprintf(stderr, "%s: %s\n", command, unsupported.c_str());
    return false;
  }
  return stack_options_from(setup.config, command, setup.options);
}

bool load_world_of(core::SystemConfig& config, const char* command, RunSetup& setup) {
  const std::string path = resolve_data_path(config.run.world);
  host_sim::WorldLoad load = host_sim::load_world(path);
  if (!load.ok()) {
    std::fprintf(stderr, "%s: world problem(s):\n%s", command, load.error_text().c_str());
    return false;
  }
  std::error_code ignored;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ignored);
  config.run.world = absolute.empty() ? path : absolute.lexically_normal().string();
  setup.world = std::move(load.world);
  return true;
}

log::LogWriterOptions log_writer_options(const core::SystemConfig& config, bool wait_when_full) {
  log::LogWriterOptions options;
  options.max_payload_bytes = log::stereo_frame_payload_size(config.camera.width_px, config.camera.height_px);
  options.wait_when_full = wait_when_full;
  return options;
}

int finish_run(const stack::Stack& stack, const core::SystemConfig& config, const RunContext& context,
               const std::string& out, const char* command) {
  RunScore score;
  const std::string error = write_run_directory(stack, config, context, out, score);
  if (!error.empty()) {
    std::fprintf(stderr, "%s: %s\n", command, error.c_str());
    return 1;
  }
  char coverage[32] = "unknown";
  if (score.coverage >= 0.0) std::snprintf(coverage, sizeof coverage, "%.1f%%", 100.0 * score.coverage);
  char ate[64] = "unknown";
  if (score.ate_rmse_m >= 0.0) {
    std::snprintf(ate, sizeof ate, "%.3f m (odometry %.3f m)", score.ate_rmse_m, score.odometry_ate_rmse_m);
  }
  std::printf("%s: %s after %.1f s simulated (%.1f s wall): coverage %s, ATE %s, %llu updates, %zu landmarks\n"
              "  map:    %s/map.pgm (+ map.yaml, map.png)\n  report: %s/report.json\n",
              command, stack::to_string(stack.stop_reason()), stack.time_s(), context.wall_time_s, coverage, ate,
              static_cast<unsigned long long>(stack.counters().updates), score.landmarks, out.c_str(), out.c_str());
  return 0;
}

}  // namespace stereoscout::cli
