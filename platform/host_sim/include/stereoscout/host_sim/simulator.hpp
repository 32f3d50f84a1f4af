#pragma once
// The simulated robot (SITL). Simulator owns the state — true pose, pan angle, simulated
// time, drive command, odometry integrator — and advances only when step(dt) is called, so
// nothing depends on wall-clock time. SimCamera (with a StereoRenderer), SimOdometry,
// SimDrive and SimClock are the platform interfaces on top of it; the application uses them
// exactly like the robot's. Kinematics-only users (planner tests) need no renderer.
//
// Kinematics: differential drive (unicycle) at the commanded velocities, clamped to the
// robot's limits (paper: 0.12 m/s, 8 deg/s), no acceleration limits. Collision: if the next
// integration step would bring the robot's disc into an obstacle of its height band, or into
// a person it does not touch where it stands, the robot stays, its command is zeroed and
// collision_count() goes up by one; a new command lets it move again. collision_event_count()
// counts contacts: a refused step when the robot was clear (2 cm) of what it last ran into
// (wall or person) since that contact; pushing on, or sliding along a wall, refused step after
// step, is one contact. People walk their loops regardless of the robot: a person who walks
// into the robot (stopped, turning, or overtaken from behind) is the person's collision, not
// the robot's; each such contact (start of an overlap) is counted in person_contact_count(),
// and lasts until they walk on (2 cm clear): the robot's steps meanwhile, after a person who
// walked through it, are no collision.
//
// Near misses (near_misses.hpp): after each step that moves the robot, the true clearance of
// its disc from the nearest static obstacle.
//
// Odometry: at robot.odometry_rate_hz the true motion since the last reading is corrupted by
// the noise model of the floor under the robot (config sim.tile / sim.carpet) and integrated
// into the odometry pose.

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "stereoscout/core/config/camera.hpp"
#include "stereoscout/core/config/robot.hpp"
#include "stereoscout/core/config/sim.hpp"
#include "stereoscout/core/messages.hpp"
#include "stereoscout/core/ring_buffer.hpp"
#include "stereoscout/host_sim/ground_truth.hpp"
#include "stereoscout/host_sim/door_visits.hpp"
#include "stereoscout/host_sim/near_misses.hpp"
#include "stereoscout/host_sim/renderer.hpp"
#include "stereoscout/host_sim/world.hpp"
#include "stereoscout/platform/camera.hpp"
#include "stereoscout/platform/clock.hpp"
#include "stereoscout/platform/drive.hpp"
#include "stereoscout/platform/odometry.hpp"

namespace stereoscout::host_sim {

// One odometry reading with the true pose at the same instant.
struct OdometrySample {
  core::OdometryReading reading;
  core::Pose2 true_pose;
};

class Simulator {
 public:
  // `world` must outlive the simulator. Allocates the odometry queue. `seed` is run.seed
  // (odometry noise stream). The camera config gives the pan unit.
  Simulator(const World& world, const core::RobotConfig& robot, const core::CameraConfig& camera,
            const core::SimConfig& sim, std::uint64_t seed);

  // Advances simulated time by dt_s (> 0) in steps of at most sim.step_s.
  void step(double dt_s);
  // Advances simulated time to `time_ns` (no-op if it is not in the future).
  void step_to(std::int64_t time_ns);

  // Drive interface: velocities are clamped to the robot's limits.
  void command(const core::DriveCommand& command);
  core::DriveCommand current_command() const { return command_; }
  void command_pan(double pan_rad);

  // Odometry readings produced so far and not yet taken (oldest first).
  bool pop_odometry(OdometrySample& sample);

  std::int64_t time_ns() const { return time_ns_; }
  double time_s() const { return static_cast<double>(time_ns_) * 1e-9; }
  const core::Pose2& true_pose() const { return pose_; }
  const core::Pose2& odometry_pose() const { return odometry_pose_; }
  double pan_rad() const { return pan_rad_; }
  std::uint64_t collision_count() const { return collisions_; }
  std::uint64_t collision_event_count() const { return collision_events_; }
  // Where the first kCollisionLogSize contacts happened (time and true pose) and what the
  // robot ran into (a person's index in World::people, or kStaticObstacle), for reports.
  static constexpr int kStaticObstacle = -1;
  struct CollisionEvent {
    double time_s = 0.0;
    core::Pose2 pose;
    int person = kStaticObstacle;
    double bearing_rad = 0.0;  // of the person's centre (or the obstacle's nearest point), from the heading
    // For a person: when they were last in a captured frame (note_frame_captured) and how far
    // from the camera; -1 when never or for a static obstacle.
    double last_in_view_s = -1.0;
    double in_view_distance_m = -1.0;
  };
  static constexpr std::size_t kCollisionLogSize = 32;
  std::size_t collision_log_size() const { return std::min<std::size_t>(collision_events_, kCollisionLogSize); }
  const CollisionEvent& collision_log(std::size_t i) const { return collision_log_[i]; }
  std::uint64_t person_collision_event_count() const { return person_collision_events_; }  // ours, into a person
  std::uint64_t person_contact_count() const { return person_contacts_; }  // a person's, into the robot
  std::uint64_t odometry_dropped() const { return odometry_queue_.overwritten(); }
  double distance_travelled_m() const { return distance_m_; }
  // Close approaches to static obstacles that touched nothing (sim.near_miss_m).
  const NearMisses& near_misses() const { return near_misses_; }
  // Passes near and through the world's doorways (sim.door_visit_reach_m).
  const DoorVisits& door_visits() const { return door_visits_; }
  const World& world() const { return world_; }
  const core::CameraConfig& camera_config() const { return camera_; }

  // Places the robot (start-up and tests); resets the odometry pose to the same pose.
  void teleport(const core::Pose2& pose);
  // A stereo pair was captured now: notes which people were in it (any part of their disc
  // within the camera's horizontal field of view, in a line of sight at the camera's height),
  // for the collision log. SimCamera calls it.
  void note_frame_captured();

 private:
  void integrate(double dt_s);
  // What the step from `here` to `there` brings the disc into: kNothing, kStaticObstacle, or
  // the index of a person it does not touch at `here`.
  static constexpr int kNothing = -2;
  int step_runs_into(const Eigen::Vector2d& here, const Eigen::Vector2d& there) const;
  // Whether the robot is still within 2 cm of what it ran into (kStaticObstacle or a person).
  bool still_touching(int target) const;
  CollisionEvent describe_collision(int hit) const;
  void count_person_contacts();
  // The disc's clearance from static obstacles, for the near misses and door visits.
  void note_clearance();
  void emit_odometry();

  const World& world_;
  core::RobotConfig robot_;
  core::CameraConfig camera_;
  core::SimConfig sim_;
  std::uint64_t seed_;
  ObstacleBand obstacles_;
  ObstacleBand sight_blockers_;  // the obstacles at the camera's height
  core::RingBuffer<OdometrySample> odometry_queue_;
  std::int64_t time_ns_ = 0;
  core::Pose2 pose_;
  core::Pose2 odometry_pose_;
  core::Pose2 pose_at_last_reading_;
  std::int64_t next_odometry_ns_ = 0;
  std::uint32_t odometry_sequence_ = 0;
  core::DriveCommand command_;
  double pan_rad_ = 0.0;
  double pan_target_rad_ = 0.0;
  std::uint64_t collisions_ = 0;
  std::uint64_t collision_events_ = 0;
  std::uint64_t person_collision_events_ = 0;
  bool in_contact_ = false;  // a step was refused and the robot has not moved clear since
  int contact_with_ = kNothing;  // what that step ran into
  std::array<CollisionEvent, kCollisionLogSize> collision_log_{};
  std::uint64_t person_contacts_ = 0;
  std::vector<std::uint8_t> person_in_contact_;  // one per person, sized at construction; set from the
                                               // overlap until the person is 2 cm clear
  std::vector<double> person_last_in_view_s_;  // one per person, -1 until first in view
  std::vector<double> person_in_view_distance_m_;
  double distance_m_ = 0.0;
  NearMisses near_misses_;
  DoorVisits door_visits_;
};

// A camera that delivers a new pair every 1 / camera.frame_rate_hz of simulated time,
// rendered from the simulator's true pose, pan angle and time (people move). grab() notes
// them; retrieve() renders the pair as it was then. The image noise is keyed by the frame's
// sequence number, so a pair is the same whether or not the pairs before it were rendered,
// and the stack renders only the one pair in several it keeps.
class SimCamera final : public platform::Camera {
 public:
  // The renderer must have been made for the simulator's world and camera config.
  SimCamera(Simulator& simulator, StereoRenderer& renderer);
  core::Status grab(core::StereoFrame& frame) override;
  core::Status retrieve(core::StereoFrame& frame) override;
  // capture(), also writing the ground-truth depth of the right image (CV_32FC1, metres).
  core::Status capture_with_depth(core::StereoFrame& frame, cv::Mat* depth_right);
  void command_pan(double pan_rad) override { simulator_.command_pan(pan_rad); }
  std::uint64_t frames_grabbed() const { return frames_; }
  std::uint64_t frames_rendered() const { return rendered_; }

 private:
  // What retrieve() renders: the scene as grab() found it.
  struct Grabbed {
    core::Pose2 true_pose;
    double pan_rad = 0.0;
    double time_s = 0.0;
    std::uint32_t frame_index = 0;
    bool pending = false;  // grabbed and not yet rendered
  };
  core::Status render_grabbed(core::StereoFrame& frame, cv::Mat* depth_right);

  Simulator& simulator_;
  StereoRenderer& renderer_;
  std::int64_t start_ns_ = 0;
  std::int64_t next_frame_ns_ = 0;
  std::uint64_t frames_ = 0;
  std::uint64_t rendered_ = 0;
  Grabbed grabbed_;
};

class SimOdometry final : public platform::Odometry {
 public:
  explicit SimOdometry(Simulator& simulator) : simulator_(simulator) {}
  core::Status read(core::OdometryReading& reading) override;
  // The true pose at the time of the last reading returned (ground-truth pose stream).
  const core::Pose2& last_true_pose() const { return last_true_pose_; }

 private:
  Simulator& simulator_;
  core::Pose2 last_true_pose_;
};

class SimDrive final : public platform::Drive {
 public:
  explicit SimDrive(Simulator& simulator) : simulator_(simulator) {}
  core::Status command(const core::DriveCommand& command) override;
  core::Status stop() override;

 private:
  Simulator& simulator_;
};

// Virtual clock: sleeping advances the simulation to the deadline.
class SimClock final : public platform::Clock {
 public:
  explicit SimClock(Simulator& simulator) : simulator_(simulator) {}
  std::int64_t now_ns() const override { return simulator_.time_ns(); }
  void sleep_until(std::int64_t deadline_ns) override;

 private:
  Simulator& simulator_;
};

}  // namespace stereoscout::host_sim
