#pragma once
// The boards the stack runs on from the command line: the simulator (explore) and a
// recorded log (replay). Each owns its platform implementations and hands the stack a
// stack::Board of interfaces; the robot's board is built in command_run.cpp.

#include <memory>
#include <string>

#include "stereoscout/core/system_config.hpp"
#include "stereoscout/host_replay/log_replay.hpp"
#include "stereoscout/host_sim/renderer.hpp"
#include "stereoscout/host_sim/simulator.hpp"
#include "stereoscout/stack/stack.hpp"

namespace stereoscout::cli {

// The simulator has no GPIO lines: the e-stop is never pressed, motor enable goes nowhere.
class SimGpio final : public platform::Gpio {
 public:
  bool emergency_stop_active() override { return false; }
  core::Status set_motor_enable(bool) override { return core::Status::success(); }
};

// A replay drives nothing: the log already holds the motion the live commands caused.
class NullDrive final : public platform::Drive {
 public:
  core::Status command(const core::DriveCommand&) override { return core::Status::success(); }
  core::Status stop() override { return core::Status::success(); }
};

class SimBoard final : public stack::GroundTruthSource {
 public:
  // `world` must outlive the board. Starts the robot at the world's start pose.
  SimBoard(const core::SystemConfig& config, const host_sim::World& world);
  stack::Board board(log::LogWriter* log);
  bool pose_at(std::int64_t timestamp_ns, core::Pose2& pose) override;
  const host_sim::Simulator& simulator() const { return simulator_; }

 private:
  host_sim::Simulator simulator_;
  host_sim::StereoRenderer renderer_;
  host_sim::SimCamera camera_;
  host_sim::SimOdometry odometry_;
  host_sim::SimDrive drive_;
  host_sim::SimClock clock_;
  SimGpio gpio_;
};

class ReplayBoard final : public stack::GroundTruthSource {
 public:
  explicit ReplayBoard(const host_replay::LogReplayOptions& options) : replay_(options) {}
  bool open(const std::string& path, std::string& error) { return replay_.open(path, error); }
  stack::Board board();
  bool pose_at(std::int64_t timestamp_ns, core::Pose2& pose) override;
  host_replay::LogReplay& replay() { return replay_; }

 private:
  host_replay::LogReplay replay_;
  NullDrive drive_;
};

}  // namespace stereoscout::cli
