// stereoscout run: the whole stack on the robot computer (platform robot_pc).

#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "arguments.hpp"
#include "commands.hpp"
#include "run_directory.hpp"
#include "run_loop.hpp"
#include "run_setup.hpp"
#include "stereoscout/report/wall_stopwatch.hpp"
#include "stereoscout/robot_pc/base_link.hpp"
#include "stereoscout/robot_pc/gpio_lines.hpp"
#include "stereoscout/robot_pc/monotonic_clock.hpp"
#include "stereoscout/robot_pc/stereo_capture.hpp"
#include "stereoscout/robot_pc/v4l2_device.hpp"

namespace stereoscout::cli {
namespace {

constexpr const char* kName = "stereoscout run";

// Set by SIGINT / SIGTERM, read by the loop: the one piece of state a signal handler may touch.
volatile std::sig_atomic_t g_stop_requested = 0;
extern "C" void request_stop(int) { g_stop_requested = 1; }

// The robot's devices, opened in the order that leaves the motors off if anything fails.
struct RobotBoard {
  robot_pc::MonotonicClock clock;
  robot_pc::GpiodLines gpio;
  std::unique_ptr<robot_pc::SerialBaseLink> base;
  std::unique_ptr<robot_pc::LinuxVideoDevice> left;
  std::unique_ptr<robot_pc::LinuxVideoDevice> right;
  std::unique_ptr<robot_pc::StereoCapture> camera;

  bool open(const core::SystemConfig& config, std::string& error) {
    const core::RobotPcConfig& pc = config.robot_pc;
    robot_pc::GpioLineConfig lines;
    lines.chip = pc.gpio_chip;
    lines.emergency_stop_line = static_cast<unsigned>(pc.emergency_stop_line);
    lines.emergency_stop_active_low = pc.emergency_stop_active_low;
    lines.motor_enable_line = static_cast<unsigned>(pc.motor_enable_line);
    if (!gpio.open(lines, error)) return false;
    base = std::make_unique<robot_pc::SerialBaseLink>(clock, static_cast<std::int64_t>(pc.base_link_timeout_ms * 1e6));
    if (!base->open(pc.base_link_device, pc.base_link_baud, error)) return false;
    robot_pc::StereoCaptureOptions options;
    options.width_px = config.camera.width_px;
    options.height_px = config.camera.height_px;
    options.buffers = pc.capture_buffers;
    options.pair_tolerance_ns = static_cast<std::int64_t>(pc.pair_tolerance_ms * 1e6);
    options.timeout_ns = static_cast<std::int64_t>(pc.capture_timeout_ms * 1e6);
    left = std::make_unique<robot_pc::LinuxVideoDevice>(pc.left_device);
    if (!left->open(error)) return false;
    if (pc.camera_mode == "side_by_side") {
      camera = std::make_unique<robot_pc::StereoCapture>(*left, clock, options);
    } else {
      right = std::make_unique<robot_pc::LinuxVideoDevice>(pc.right_device);
      if (!right->open(error)) return false;
      camera = std::make_unique<robot_pc::StereoCapture>(*left, *right, clock, options);
    }
    return camera->start(error);
  }

  stack::Board board(log::LogWriter* log) {
    stack::Board board;
    board.camera = camera.get();
    board.odometry = base.get();
    board.drive = base.get();
    board.gpio = &gpio;
    board.clock = &clock;
    board.log = log;
    return board;
  }
};

}  // namespace

int run_run(int argc, char** argv) {
  Arguments arguments("run",
                      "Runs the whole stack on the robot computer: V4L2 stereo cameras, the serial base link\n"
                      "(odometry and drive), the e-stop and motor-enable GPIO lines, the monotonic clock.\n"
                      "Explores until done, the time limit, or Ctrl-C; records the sensor log for replay and\n"
                      "writes the run directory (docs/deploy.md).");
  arguments.option("config", "FILE", "config file (the robot's devices are in section robot_pc)", default_config_path());
  arguments.option("max-time", "SEC", "stop after this much time (default: run.max_time_s)");
  arguments.option("localization", "SOURCE", "pose source: rbpf or odometry (default: run.localization)");
  arguments.option("out", "DIR", "run directory (created)", "runs/robot");
  arguments.flag("no-log", "do not record the sensor log");
  if (!arguments.parse(argc, argv)) return arguments.exit_code();
  const auto wall_start = std::chrono::steady_clock::now();
  RunSetup setup;
  if (!load_run_setup(arguments, kName, setup)) return 2;
  if (setup.options.localization == stack::Localization::groundtruth) {
    std::fprintf(stderr, "%s: run.localization 'groundtruth' needs the simulator; use rbpf or odometry\n", kName);
    return 2;
  }
  const std::string out = arguments.get("out");
  std::error_code ignored;
  std::filesystem::create_directories(out, ignored);
  std::string error;
  RobotBoard robot;
  if (!robot.open(setup.config, error)) {
    std::fprintf(stderr, "%s: %s\n", kName, error.c_str());
    return 1;
  }
  log::LogWriter writer(log_writer_options(setup.config, false));
  const bool record = !arguments.has("no-log");
  if (record && !writer.open(out + "/sensors.log", error)) {
    std::fprintf(stderr, "%s: %s\n", kName, error.c_str());
    return 1;
  }
  std::signal(SIGINT, request_stop);
  std::signal(SIGTERM, request_stop);
  report::WallStopwatch stopwatch;
  stack::Stack stack(setup.config, setup.options, robot.board(record ? &writer : nullptr), stopwatch);
  if (!stack.start(kStartTimeoutS, error)) {
    std::fprintf(stderr, "%s: %s (base link %s)\n", kName, error.c_str(), setup.config.robot_pc.base_link_device.c_str());
    return 1;
  }
  LoopHooks hooks;
  hooks.should_stop = [] { return g_stop_requested != 0; };
  run_to_end(stack, hooks);
  stack.finish();
  robot.gpio.set_motor_enable(false);
  robot.camera->stop();

  RunContext context;
  context.command = "run";
  context.log_file = record ? "sensors.log" : "";
  context.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return finish_run(stack, setup.config, context, out, kName);
}

}  // namespace stereoscout::cli
