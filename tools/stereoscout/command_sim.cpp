// stereoscout sim-render / world-map: look at a simulated world (platform/host_sim).
#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <filesystem>
#include <sstream>

#include "arguments.hpp"
#include "commands.hpp"
#include "rendered_scan.hpp"
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

namespace {

// Where a scan column's point falls, against the world's real obstacles (people left out).
struct ScanScore {
  long long views = 0;
  long long at_obstacle = 0;       // obstacle columns within 0.1 m of a real obstacle
  long long near_obstacle = 0;     // 0.1-0.3 m
  long long short_of_obstacle = 0;  // 0.3-0.6 m (a wall placed where its matched floor ends)
  long long in_free_space = 0;     // farther than 0.6 m: a phantom
  long long free_columns = 0;
  long long free_through_obstacle = 0;  // free space reported across a real obstacle
  long long free_past_obstacle_far = 0;  // ... ending more than kNear_m beyond where it entered it
};

constexpr double kAt_m = 0.1;
constexpr double kNear_m = 0.3;
constexpr double kShort_m = 0.6;
constexpr double kRayStep_m = 0.05;

void score_scan(const core::DepthScan& scan, const core::Pose2& pose, const host_sim::ObstacleBand& band,
                double within_m, ScanScore& score) {
  const Eigen::Rotation2Dd to_world(pose.theta);
  const Eigen::Vector2d origin = pose.translation() + to_world * scan.origin_robot;
  for (const core::DepthScanColumn& column : scan.columns) {
    const Eigen::Vector2d point = pose.translation() + to_world * Eigen::Vector2d(column.x_robot_m, column.y_robot_m);
    const double range = (point - origin).norm();
    if (column.kind == core::DepthScanColumn::Kind::invalid || range > within_m) continue;
    if (column.kind == core::DepthScanColumn::Kind::free) {
      ++score.free_columns;
      for (double s = kRayStep_m; s < range - kRayStep_m; s += kRayStep_m) {
        if (band.disc_collides(origin + (point - origin) * (s / range), 0.01)) {
          ++score.free_through_obstacle;
          if (range - s > kNear_m) ++score.free_past_obstacle_far;
          break;
        }
      }
    } else if (band.disc_collides(point, kAt_m)) {
      ++score.at_obstacle;
    } else if (band.disc_collides(point, kNear_m)) {
      ++score.near_obstacle;
    } else if (band.disc_collides(point, kShort_m)) {
      ++score.short_of_obstacle;
    } else {
      ++score.in_free_space;
    }
  }
}

}  // namespace

int run_eval_scan(int argc, char** argv) {
  Arguments arguments("eval-scan",
                      "Scores the 2.5D obstacle scan of the vision front end on rendered views of a world:\n"
                      "from every pose of a grid over its free space (the robot's disc and 0.1 m clear)\n"
                      "at evenly spaced headings, each column within --within metres is placed against\n"
                      "the world's real obstacles (walking people left out). Prints JSON: obstacle\n"
                      "columns within 0.1 m of an obstacle, 0.1-0.3 m, 0.3-0.6 m, and farther (in free\n"
                      "space), free columns, free columns whose ray crosses an obstacle, and those\n"
              "of them that end more than 0.3 m past where they entered it (a wall erased, not\n"
              "a grazed corner).");
  arguments.option("config", "FILE", "config file (camera, vision, robot, sim sections)", default_config_path());
  arguments.option("world", "FILE", "world file (default: run.world of the config)");
  arguments.option("grid", "M", "spacing of the poses in metres", "1.5");
  arguments.option("headings", "N", "headings per pose", "12");
  arguments.option("within", "M", "columns farther than this from the camera are not scored", "2.5");
  if (!arguments.parse(argc, argv)) return arguments.exit_code();
  core::SystemConfig config;
  host_sim::World world;
  if (!load_inputs(arguments, "eval-scan", config, world)) return 1;
  double grid_m = 1.5;
  double within_m = 2.5;
  long long headings = 12;
  if (!arguments.get_double("grid", grid_m) || !arguments.get_double("within", within_m) ||
      !arguments.get_int("headings", headings)) {
    return 2;
  }
  if (!(grid_m >= 0.1) || !(within_m > 0.0) || headings < 1 || headings > 360) {
    std::fprintf(stderr, "stereoscout eval-scan: need --grid >= 0.1, --within > 0, --headings in [1, 360]\n");
    return 2;
  }
  const std::string unsupported = host_sim::check_camera_supported(config.camera);
  if (!unsupported.empty()) {
    std::fprintf(stderr, "stereoscout eval-scan: %s\n", unsupported.c_str());
    return 1;
  }
  world.people.clear();
  const host_sim::ObstacleBand band(world, config.sim.floor_tolerance_m, config.robot.height_m);
  RenderedScanner scanner(world, config);
  ScanScore score;
  const Eigen::Vector2d low = world.bounds_min();
  const Eigen::Vector2d high = world.bounds_max();
  for (double x = low.x() + 0.5 * grid_m; x < high.x(); x += grid_m) {
    for (double y = low.y() + 0.5 * grid_m; y < high.y(); y += grid_m) {
      if (band.disc_collides({x, y}, config.robot.radius_m + 0.1)) continue;
      for (long long k = 0; k < headings; ++k) {
        const core::Pose2 pose{x, y, core::wrap_angle(2.0 * core::kPi * static_cast<double>(k) / static_cast<double>(headings))};
        if (!scanner.scan_at(pose, static_cast<std::uint32_t>(score.views))) continue;
        ++score.views;
        score_scan(scanner.scan(), pose, band, within_m, score);
      }
    }
  }
  std::printf("{\"world\": \"%s\", \"views\": %lld, \"within_m\": %g,\n"
              " \"obstacle_columns\": {\"within_0.1_m\": %lld, \"0.1_to_0.3_m\": %lld, \"0.3_to_0.6_m\": %lld, "
              "\"in_free_space\": %lld},\n"
              " \"free_columns\": %lld, \"free_through_obstacle\": %lld, \"free_past_obstacle_by_0.3_m\": %lld}\n",
              world.name.c_str(), score.views, within_m, score.at_obstacle, score.near_obstacle,
              score.short_of_obstacle, score.in_free_space, score.free_columns, score.free_through_obstacle,
              score.free_past_obstacle_far);
  return 0;
}

}  // namespace stereoscout::cli
