#include "boards.hpp"

namespace stereoscout::cli {

SimBoard::SimBoard(const core::SystemConfig& config, const host_sim::World& world)
    : simulator_(world, config.robot, config.camera, config.sim, static_cast<std::uint64_t>(config.run.seed)),
      renderer_(world, config.camera, config.sim, static_cast<std::uint64_t>(config.run.seed)),
      camera_(simulator_, renderer_),
      odometry_(simulator_),
      drive_(simulator_),
      clock_(simulator_) {
  simulator_.teleport(world.start);
}

stack::Board SimBoard::board(log::LogWriter* log) {
  stack::Board board;
  board.camera = &camera_;
  board.odometry = &odometry_;
  board.drive = &drive_;
  board.gpio = &gpio_;
  board.clock = &clock_;
  board.ground_truth = this;
  board.log = log;
  return board;
}

// The stack asks right after a capture, and the simulator renders at the current time.
bool SimBoard::pose_at(std::int64_t timestamp_ns, core::Pose2& pose) {
  if (timestamp_ns != simulator_.time_ns()) return false;
  pose = simulator_.true_pose();
  return true;
}

stack::Board ReplayBoard::board() {
  stack::Board board;
  board.camera = &replay_.camera();
  board.odometry = &replay_.odometry();
  board.drive = &drive_;
  board.gpio = &replay_.gpio();
  board.clock = &replay_.clock();
  board.ground_truth = this;
  return board;
}

// The live run logged the true pose right after each kept pair, with the pair's time.
bool ReplayBoard::pose_at(std::int64_t timestamp_ns, core::Pose2& pose) {
  std::int64_t logged_ns = 0;
  return replay_.latest_ground_truth(logged_ns, pose) && logged_ns == timestamp_ns;
}

}  // namespace stereoscout::cli
