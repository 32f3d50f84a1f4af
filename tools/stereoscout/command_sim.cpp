// stereoscout sim-render / world-map: look at a simulated world (platform/host_sim).
#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "arguments.hpp"
#include "commands.hpp"
#include "stereoscout/core/system_config.hpp"
#include "stereoscout/host_sim/ground_truth.hpp"
#include "stereoscout/host_sim/renderer.hpp"
#include "stereoscout/host_sim/world.hpp"

namespace stereoscout::cli {
namespace {

// Parses "x,y,theta_deg".
bool parse_pose(const std::string& text, core::Pose2& pose) {
  std::istringstream stream(text);
  double values[3];
  char comma = 0;
  if (!(stream >> values[0] >> comma >> values[1]) || comma != ',') return false;
  if (!(stream >> comma >> values[2]) || comma != ',') return false;
  if (!stream.eof() && stream.peek() != EOF) return false;
  pose = core::Pose2{values[0], values[1], core::wrap_angle(core::degrees_to_radians(values[2]))};
  return true;
}

// Loads the config and the world (the --world option, else run.world); prints errors.
bool load_inputs(const Arguments& arguments, const char* command, core::SystemConfig& config, host_sim::World& world) {
  const core::SystemConfigLoad load = core::load_system_config(arguments.get("config"));
  if (!load.ok()) {
    std::fprintf(stderr, "stereoscout %s: config problem(s):\n%s", command, load.error_text().c_str());
    return false;
  }
  config = load.config;
  const std::string world_path = resolve_data_path(arguments.has("world") ? arguments.get("world") : config.run.world);
  host_sim::WorldLoad world_load = host_sim::load_world(world_path);
  if (!world_load.ok()) {
    std::fprintf(stderr, "stereoscout %s: world problem(s):\n%s", command, world_load.error_text().c_str());
    return false;
  }
  world = std::move(world_load.world);
  return true;
}

bool make_directory(const std::string& path, const char* command) {
  std::error_code error;
  std::filesystem::create_directories(path, error);
  if (error) {
    std::fprintf(stderr, "stereoscout %s: cannot create %s: %s\n", command, path.c_str(), error.message().c_str());
    return false;
  }
  return true;
}

}  // namespace

int run_sim_render(int argc, char** argv) {
  Arguments arguments("sim-render",
                      "Renders the stereo pair the simulated camera sees from a robot pose and writes\n"
                      "left.png, right.png (8-bit) and depth.png (16-bit, millimetres along the\n"
                      "optical axis of the right camera, 0 = nothing) into the output directory.");
  arguments.option("config", "FILE", "config file (camera, sim sections)", default_config_path());
  arguments.option("world", "FILE", "world file (default: run.world of the config)");
  arguments.option("pose", "X,Y,THETA", "robot pose in the world: metres, metres, degrees (default: the world's start)");
  arguments.option("pan", "DEG", "pan unit angle in degrees", "0");
  arguments.option("time", "S", "simulated time in seconds (where the people are)", "0");
  arguments.option("out", "DIR", "output directory", ".");
  if (!arguments.parse(argc, argv)) return arguments.exit_code();
  core::SystemConfig config;
  host_sim::World world;
  if (!load_inputs(arguments, "sim-render", config, world)) return 1;
  core::Pose2 pose = world.start;
  if (arguments.has("pose") && !parse_pose(arguments.get("pose"), pose)) {
    std::fprintf(stderr, "stereoscout sim-render: --pose: expected X,Y,THETA_DEG, got '%s'\n", arguments.get("pose").c_str());
    return 2;
  }
  double pan_deg = 0.0;
  double time_s = 0.0;
  if (!arguments.get_double("pan", pan_deg) || !arguments.get_double("time", time_s)) return 2;
  const std::string unsupported = host_sim::check_camera_supported(config.camera);
  if (!unsupported.empty()) {
    std::fprintf(stderr, "stereoscout sim-render: %s\n", unsupported.c_str());
    return 1;
  }
  const std::string out = arguments.get("out");
  if (!make_directory(out, "sim-render")) return 1;
  host_sim::StereoRenderer renderer(world, config.camera, config.sim, static_cast<std::uint64_t>(config.run.seed));
  cv::Mat left(config.camera.height_px, config.camera.width_px, CV_8UC1);
  cv::Mat right(config.camera.height_px, config.camera.width_px, CV_8UC1);
  cv::Mat depth(config.camera.height_px, config.camera.width_px, CV_32FC1);
  renderer.render(pose, core::degrees_to_radians(pan_deg), time_s, 0, left, right, &depth);
  cv::Mat depth_mm;
  depth.convertTo(depth_mm, CV_16UC1, 1000.0);
  const bool written = cv::imwrite(out + "/left.png", left) && cv::imwrite(out + "/right.png", right) &&
                       cv::imwrite(out + "/depth.png", depth_mm);
  if (!written) {
    std::fprintf(stderr, "stereoscout sim-render: cannot write the images into %s\n", out.c_str());
    return 1;
  }
  std::printf("wrote %s/left.png, right.png, depth.png (pose %.3f, %.3f, %.1f deg, pan %.1f deg)\n", out.c_str(), pose.x,
              pose.y, core::radians_to_degrees(pose.theta), pan_deg);
  return 0;
}

int run_world_map(int argc, char** argv) {
  Arguments arguments("world-map",
                      "Writes the ground truth of a world for the robot's height band: map.pgm and\n"
                      "map.yaml (ROS map_server: 0 occupied, 254 free) and reachable.pgm (254 where\n"
                      "the robot's centre can go from the start pose, 0 occupied, 205 elsewhere).");
  arguments.option("config", "FILE", "config file (robot and sim sections)", default_config_path());
  arguments.option("world", "FILE", "world file (default: run.world of the config)");
  arguments.option("resolution", "M", "cell size in metres", "0.05");
  arguments.option("out", "DIR", "output directory", ".");
  if (!arguments.parse(argc, argv)) return arguments.exit_code();
  core::SystemConfig config;
  host_sim::World world;
  if (!load_inputs(arguments, "world-map", config, world)) return 1;
  double resolution = 0.05;
  if (!arguments.get_double("resolution", resolution)) return 2;
  if (!(resolution >= 0.005 && resolution <= 5.0)) {
    std::fprintf(stderr, "stereoscout world-map: --resolution must be in [0.005, 5] m\n");
    return 2;
  }
  const std::string out = arguments.get("out");
  if (!make_directory(out, "world-map")) return 1;
  const host_sim::GroundTruthGrid map =
      host_sim::rasterize_world(world, resolution, config.sim.floor_tolerance_m, config.robot.height_m);
  const host_sim::GroundTruthGrid reachable =
      host_sim::reachable_free_space(map, world.start.translation(), config.robot.radius_m);
  for (const std::string& error : {host_sim::write_map_pgm(map, out + "/map.pgm"),
                                   host_sim::write_map_yaml(map, out + "/map.yaml", "map.pgm"),
                                   host_sim::write_map_pgm(reachable, out + "/reachable.pgm")}) {
    if (!error.empty()) {
      std::fprintf(stderr, "stereoscout world-map: %s\n", error.c_str());
      return 1;
    }
  }
  const double cell_area = resolution * resolution;
  std::printf("wrote %s/map.pgm, map.yaml, reachable.pgm: %d x %d cells of %g m; occupied %.2f m2, reachable %.2f m2\n",
              out.c_str(), map.width, map.height, resolution,
              static_cast<double>(map.count(host_sim::GroundTruthGrid::occupied)) * cell_area,
              static_cast<double>(reachable.count(host_sim::GroundTruthGrid::free)) * cell_area);
  return 0;
}

}  // namespace stereoscout::cli
