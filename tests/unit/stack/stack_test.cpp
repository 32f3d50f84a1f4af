// The stack's tick table on a scripted board: a robot that moves as commanded, a camera
// whose pan unit can be frozen, an e-stop pressed for a while.
#include "stereoscout/stack/stack.hpp"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "stereoscout/core/random.hpp"

namespace stereoscout::stack {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

core::SystemConfig small_config() {
  core::SystemConfig config;
  config.run.max_time_s = 60.0;
  config.camera.width_px = 160;
  config.camera.height_px = 120;
  config.camera.focal_px = 100.0;
  config.camera.principal_x_px = 79.5;
  config.camera.principal_y_px = 59.5;
  config.vision.max_features = 100;
  config.vision.dense_num_disparities = 16;
  config.vision.max_disparity_px = 32;
  config.filter.particles = 10;
  config.filter.particle_capacity = 10;
  config.filter.landmark_node_capacity = 50000;
  config.filter.landmark_estimate_capacity = 20000;
  config.filter.trajectory_node_capacity = 5000;
  config.grid.width_cells = 100;
  config.grid.height_cells = 100;
  config.grid.scan_history = 64;
  return config;
}

// A robot that integrates its drive command, with odometry readings at 5.4 Hz and stereo
// pairs (a fixed random texture) at 15 Hz, on a virtual clock.
class ScriptedRobot final : public platform::Camera, public platform::Odometry, public platform::Drive,
                            public platform::Gpio, public platform::Clock {
 public:
  explicit ScriptedRobot(const core::CameraConfig& camera) {
    texture_.create(camera.height_px, camera.width_px, CV_8UC1);
    core::RandomStream random(3, {core::stream_purpose::test, 0, 0});
    for (int y = 0; y < texture_.rows; ++y) {
      for (int x = 0; x < texture_.cols; ++x) texture_.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(random.uniform() * 255.0);
    }
  }

  // Clock: advancing time moves the robot and produces the readings that fall due.
  std::int64_t now_ns() const override { return now_ns_; }
  void sleep_until(std::int64_t deadline_ns) override {
    while (now_ns_ < deadline_ns) {
      const std::int64_t step = std::min<std::int64_t>(deadline_ns - now_ns_, kSecond / 100);
      const double dt = static_cast<double>(step) * 1e-9;
      pose_ = pose_.compose(core::Pose2{command_.linear_mps * dt, 0.0, command_.angular_rad_s * dt});
      const double pan_step = std::clamp(pan_target_ - pan_, -kPanRate * dt, kPanRate * dt);
      pan_ += pan_step;
      now_ns_ += step;
    }
  }

  core::Status grab(core::StereoFrame& frame) override {
    if (now_ns_ < next_frame_ns_) return {core::StatusCode::not_available, "no pair yet"};
    next_frame_ns_ += kSecond / 15;
    texture_.copyTo(frame.left);
    texture_.copyTo(frame.right);
    frame.timestamp_ns = now_ns_;
    frame.sequence = sequence_++;
    frame.pan_rad = pan_frozen ? 0.0 : pan_;
    return core::Status::success();
  }
  void command_pan(double pan_rad) override { pan_target_ = pan_rad; }

  core::Status read(core::OdometryReading& reading) override {
    if (now_ns_ < next_odometry_ns_) return {core::StatusCode::not_available, "no reading yet"};
    reading.timestamp_ns = now_ns_;
    reading.sequence = odometry_sequence_++;
    reading.pose = pose_;
    next_odometry_ns_ = now_ns_ + static_cast<std::int64_t>(kSecond / 5.4);
    return core::Status::success();
  }

  core::Status command(const core::DriveCommand& command) override {
    if (estop_active() && (command.linear_mps != 0.0 || command.angular_rad_s != 0.0)) ++moved_during_estop;
    command_ = estop_active() ? core::DriveCommand{} : command;
    return core::Status::success();
  }
  core::Status stop() override {
    command_ = core::DriveCommand{};
    ++stops;
    return core::Status::success();
  }

  bool emergency_stop_active() override { return estop_active(); }
  core::Status set_motor_enable(bool enabled) override {
    motor_enabled = enabled;
    return core::Status::success();
  }

  bool estop_active() const { return now_ns_ >= estop_from_ns && now_ns_ < estop_until_ns; }

  Board board() {
    Board board;
    board.camera = this;
    board.odometry = this;
    board.drive = this;
    board.gpio = this;
    board.clock = this;
    return board;
  }

  std::int64_t estop_from_ns = -1;
  std::int64_t estop_until_ns = -1;
  bool pan_frozen = false;
  std::uint64_t moved_during_estop = 0;
  std::uint64_t stops = 0;
  bool motor_enabled = false;
  core::Pose2 pose_;

 private:
  cv::Mat texture_;
  std::int64_t now_ns_ = 0;
  std::int64_t next_frame_ns_ = 0;
  std::int64_t next_odometry_ns_ = kSecond / 5;
  std::uint64_t sequence_ = 0;
  std::uint64_t odometry_sequence_ = 0;
  core::DriveCommand command_;
  double pan_ = 0.0;
  double pan_target_ = 0.0;
  static constexpr double kPanRate = 30.0 * M_PI / 180.0;  // the paper's pan unit
};

class NullTime final : public core::TimeSource {
 public:
  std::int64_t now_ns() const override { return 0; }
};

struct StackFixture {
  explicit StackFixture(const core::SystemConfig& config) : robot(config.camera) {
    stack = std::make_unique<Stack>(config, StackOptions{}, robot.board(), stopwatch);
  }
  void run_until(std::int64_t t_ns) {
    while (robot.now_ns() < t_ns && stack->tick()) {
    }
  }
  ScriptedRobot robot;
  NullTime stopwatch;
  std::unique_ptr<Stack> stack;
};

TEST(Stack, StartsAtTheFirstOdometryReadingAndKeepsOnlyPairsAfterMotion) {
  StackFixture f(small_config());
  f.robot.pan_frozen = true;                  // the pan unit does not turn
  f.robot.estop_from_ns = 0;                  // and the e-stop keeps the wheels still
  f.robot.estop_until_ns = 100 * kSecond;
  std::string error;
  ASSERT_TRUE(f.stack->start(5.0, error)) << error;
  EXPECT_EQ(f.robot.now_ns(), kSecond / 5);  // polled until the first reading
  f.run_until(4 * kSecond);
  const StackCounters& c = f.stack->counters();
  EXPECT_GE(c.frames_captured, 55U);
  EXPECT_EQ(c.frames_kept, 1U);  // nothing moved after the first pair
  EXPECT_EQ(c.updates, 1U);
  EXPECT_EQ(c.heap_allocations_in_loop, 0U);
  EXPECT_GT(c.heap_allocations_in_sift, 0U);  // OpenCV's SIFT, counted apart
}

TEST(Stack, EmergencyStopHoldsTheRobotAndTheMotorsOffUntilReleased) {
  StackFixture f(small_config());
  f.robot.estop_from_ns = 2 * kSecond;
  f.robot.estop_until_ns = 4 * kSecond;
  std::string error;
  ASSERT_TRUE(f.stack->start(5.0, error)) << error;
  f.run_until(2 * kSecond);
  EXPECT_TRUE(f.robot.motor_enabled);
  f.run_until(3 * kSecond);
  EXPECT_FALSE(f.robot.motor_enabled);
  EXPECT_GT(f.robot.stops, 40U);  // every safety tick (50 Hz) while pressed
  const core::Pose2 held = f.robot.pose_;
  f.run_until(4 * kSecond - kSecond / 50);
  EXPECT_EQ(f.robot.pose_.x, held.x);
  EXPECT_EQ(f.robot.pose_.theta, held.theta);
  f.run_until(5 * kSecond);
  EXPECT_TRUE(f.robot.motor_enabled);
  EXPECT_EQ(f.robot.moved_during_estop, 0U);
  EXPECT_GT(f.stack->counters().emergency_stop_ticks, 90U);
  EXPECT_EQ(f.stack->counters().heap_allocations_in_loop, 0U);
}

TEST(Stack, StopsAtTheTimeLimit) {
  core::SystemConfig config = small_config();
  StackOptions options;
  options.max_time_s = 2.0;
  ScriptedRobot robot(config.camera);
  NullTime stopwatch;
  Stack stack(config, options, robot.board(), stopwatch);
  std::string error;
  ASSERT_TRUE(stack.start(5.0, error)) << error;
  while (stack.tick()) {
  }
  EXPECT_EQ(stack.stop_reason(), StopReason::time_limit);
  EXPECT_NEAR(stack.time_s(), 2.0, 0.05);
}

}  // namespace
}  // namespace stereoscout::stack
