#include "stereoscout/host_sim/simulator.hpp"

#include <algorithm>
#include <cmath>

#include "stereoscout/core/odometry_noise.hpp"
#include "stereoscout/core/random.hpp"

namespace stereoscout::host_sim {
namespace {

// A contact ends when the robot's disc is this far clear of the obstacle or person; so does a
// near miss's approach.
constexpr double kContactClearance_m = 0.02;

std::int64_t seconds_to_ns(double seconds) { return static_cast<std::int64_t>(std::llround(seconds * 1e9)); }

}  // namespace

Simulator::Simulator(const World& world, const core::RobotConfig& robot, const core::CameraConfig& camera,
                     const core::SimConfig& sim, std::uint64_t seed)
    : world_(world),
      robot_(robot),
      camera_(camera),
      sim_(sim),
      seed_(seed),
      obstacles_(world, sim.floor_tolerance_m, robot.height_m),
      sight_blockers_(world, camera.mount_height_m, camera.mount_height_m),
      odometry_queue_(static_cast<std::size_t>(sim.odometry_queue)),
      person_in_contact_(world.people.size(), 0),
      person_last_in_view_s_(world.people.size(), -1.0),
      person_in_view_distance_m_(world.people.size(), -1.0),
      near_misses_(sim.near_miss_m, kContactClearance_m),
      door_visits_(world.doorways, sim.door_visit_reach_m > 0.0 ? robot.radius_m + sim.door_visit_reach_m : 0.0,
                   kContactClearance_m) {
  teleport(world.start);
}

void Simulator::teleport(const core::Pose2& pose) {
  pose_ = pose;
  odometry_pose_ = pose;
  pose_at_last_reading_ = pose;
  next_odometry_ns_ = time_ns_ + seconds_to_ns(1.0 / robot_.odometry_rate_hz);
}

void Simulator::command(const core::DriveCommand& command) {
  const double max_turn = core::degrees_to_radians(robot_.max_turn_rate_deg_s);
  command_.linear_mps = std::clamp(command.linear_mps, -robot_.max_speed_mps, robot_.max_speed_mps);
  command_.angular_rad_s = std::clamp(command.angular_rad_s, -max_turn, max_turn);
  if (!std::isfinite(command_.linear_mps) || !std::isfinite(command_.angular_rad_s)) command_ = core::DriveCommand{};
}

void Simulator::command_pan(double pan_rad) {
  if (camera_.has_pan_unit && std::isfinite(pan_rad)) pan_target_rad_ = core::wrap_angle(pan_rad);
}

int Simulator::step_runs_into(const Eigen::Vector2d& here, const Eigen::Vector2d& there) const {
  if (obstacles_.disc_collides(there, robot_.radius_m)) return kStaticObstacle;
  for (std::size_t i = 0; i < world_.people.size(); ++i) {
    // Ours only when the step makes a contact that standing still would not have: a contact
    // the person made (walking into the robot, overtaking it) lasts until they walk on. The
    // simulated people walk through the robot; one who did so and is just leaving ahead of it
    // has not been run into by its next step.
    if (person_in_contact_[i] != 0) continue;
    const Eigen::Vector2d person = world_.person_position(i, time_s());
    const double limit = robot_.radius_m + world_.people[i].radius;
    if ((person - there).norm() < limit && (person - here).norm() >= limit) return static_cast<int>(i);
  }
  return kNothing;
}

Simulator::CollisionEvent Simulator::describe_collision(int hit) const {
  CollisionEvent event{time_s(), pose_, hit};
  Eigen::Vector2d target;
  if (hit == kStaticObstacle) {
    target = obstacles_.nearest_point(pose_.translation());
  } else {
    const auto i = static_cast<std::size_t>(hit);
    target = world_.person_position(i, time_s());
    event.last_in_view_s = person_last_in_view_s_[i];
    event.in_view_distance_m = person_in_view_distance_m_[i];
  }
  const Eigen::Vector2d offset = target - pose_.translation();
  event.bearing_rad = core::wrap_angle(std::atan2(offset.y(), offset.x()) - pose_.theta);
  return event;
}

void Simulator::note_frame_captured() {
  const double heading = pose_.theta + pan_rad_;
  const Eigen::Vector2d camera = pose_.transform_point({camera_.mount_x_m, camera_.mount_y_m});
  const double half_view = std::atan2(0.5 * camera_.width_px, camera_.focal_px);
  for (std::size_t i = 0; i < world_.people.size(); ++i) {
    const Eigen::Vector2d offset = world_.person_position(i, time_s()) - camera;
    const double distance = offset.norm();
    const double radius = world_.people[i].radius;
    const double half_width = distance > radius ? std::asin(radius / distance) : core::kPi;
    const double bearing = core::wrap_angle(std::atan2(offset.y(), offset.x()) - heading);
    if (std::abs(bearing) - half_width >= half_view) continue;
    if (sight_blockers_.blocks_line(camera, camera + offset)) continue;
    person_last_in_view_s_[i] = time_s();
    person_in_view_distance_m_[i] = distance;
  }
}

bool Simulator::still_touching(int target) const {
  if (target == kStaticObstacle) return obstacles_.disc_collides(pose_.translation(), robot_.radius_m + kContactClearance_m);
  const auto i = static_cast<std::size_t>(target);
  const double distance = (world_.person_position(i, time_s()) - pose_.translation()).norm();
  return distance < robot_.radius_m + world_.people[i].radius + kContactClearance_m;
}

void Simulator::count_person_contacts() {
  for (std::size_t i = 0; i < world_.people.size(); ++i) {
    const double distance = (world_.person_position(i, time_s()) - pose_.translation()).norm();
    const double limit = robot_.radius_m + world_.people[i].radius;
    if (distance < limit) {
      if (person_in_contact_[i] == 0) ++person_contacts_;
      person_in_contact_[i] = 1;
    } else if (distance >= limit + kContactClearance_m) {
      person_in_contact_[i] = 0;
    }
  }
}

void Simulator::integrate(double dt_s) {
  // Pan unit: turns toward its target at its rate along the shorter way.
  const double pan_error = core::wrap_angle(pan_target_rad_ - pan_rad_);
  const double pan_step = core::degrees_to_radians(camera_.pan_rate_deg_s) * dt_s;
  pan_rad_ = core::wrap_angle(pan_rad_ + std::clamp(pan_error, -pan_step, pan_step));
  if (command_.linear_mps != 0.0 || command_.angular_rad_s != 0.0) {
    // Unicycle, midpoint heading (exact for straight lines and turns in place).
    const double turn = command_.angular_rad_s * dt_s;
    const double heading = pose_.theta + 0.5 * turn;
    const double travel = command_.linear_mps * dt_s;
    const core::Pose2 next{pose_.x + travel * std::cos(heading), pose_.y + travel * std::sin(heading),
                           core::wrap_angle(pose_.theta + turn)};
    const int hit = step_runs_into(pose_.translation(), next.translation());
    if (hit != kNothing) {
      ++collisions_;
      if (!in_contact_) {
        if (collision_events_ < kCollisionLogSize) collision_log_[collision_events_] = describe_collision(hit);
        ++collision_events_;
        if (hit != kStaticObstacle) ++person_collision_events_;
      }
      if (hit == kStaticObstacle) {
        near_misses_.touched();
        door_visits_.touched();
      }
      in_contact_ = true;
      contact_with_ = hit;
      command_ = core::DriveCommand{};
    } else {
      pose_ = next;
      distance_m_ += std::abs(travel);
      if (travel != 0.0) note_clearance();
      // The contact lasts until the robot has moved clear: sliding along a wall, refused step
      // after step, is one contact.
      in_contact_ = in_contact_ && still_touching(contact_with_);
    }
  }
  count_person_contacts();
}

void Simulator::note_clearance() {
  if (near_misses_.threshold_m() <= 0.0 && !door_visits_.active()) return;
  const Eigen::Vector2d centre = pose_.translation();
  const double clearance = (obstacles_.nearest_point(centre) - centre).norm() - robot_.radius_m;
  near_misses_.moved(time_s(), pose_, clearance);
  door_visits_.moved(time_s(), pose_, clearance);
}

void Simulator::emit_odometry() {
  const core::Pose2 delta = pose_at_last_reading_.between(pose_);
  const core::OdometryNoiseConfig& noise =
      world_.floor_type_at(pose_.translation()) == FloorType::carpet ? sim_.carpet : sim_.tile;
  core::RandomStream random(seed_, {core::stream_purpose::sim_odometry, odometry_sequence_, 0});
  odometry_pose_ = odometry_pose_.compose(core::corrupt_motion(delta, noise, random));
  pose_at_last_reading_ = pose_;
  OdometrySample& sample = odometry_queue_.next_slot_overwrite();
  sample.reading.timestamp_ns = time_ns_;
  sample.reading.sequence = odometry_sequence_++;
  sample.reading.pose = odometry_pose_;
  sample.true_pose = pose_;
}

void Simulator::step(double dt_s) {
  if (dt_s > 0.0) step_to(time_ns_ + seconds_to_ns(dt_s));
}

void Simulator::step_to(std::int64_t end_ns) {
  const std::int64_t max_step_ns = std::max<std::int64_t>(1, seconds_to_ns(sim_.step_s));
  const std::int64_t odometry_period_ns = std::max<std::int64_t>(1, seconds_to_ns(1.0 / robot_.odometry_rate_hz));
  while (time_ns_ < end_ns) {
    const std::int64_t step_ns = std::min({max_step_ns, end_ns - time_ns_, next_odometry_ns_ - time_ns_});
    integrate(static_cast<double>(step_ns) * 1e-9);
    time_ns_ += step_ns;
    if (time_ns_ >= next_odometry_ns_) {
      emit_odometry();
      next_odometry_ns_ += odometry_period_ns;
    }
  }
}

bool Simulator::pop_odometry(OdometrySample& sample) {
  if (odometry_queue_.empty()) return false;
  sample = odometry_queue_.front();
  odometry_queue_.pop_front();
  return true;
}

SimCamera::SimCamera(Simulator& simulator, StereoRenderer& renderer)
    : simulator_(simulator), renderer_(renderer), start_ns_(simulator.time_ns()), next_frame_ns_(simulator.time_ns()) {}

core::Status SimCamera::grab(core::StereoFrame& frame) {
  if (simulator_.time_ns() < next_frame_ns_) return {core::StatusCode::not_available, "no new stereo pair yet"};
  grabbed_.true_pose = simulator_.true_pose();
  grabbed_.pan_rad = simulator_.pan_rad();
  grabbed_.time_s = simulator_.time_s();
  grabbed_.frame_index = static_cast<std::uint32_t>(frames_);
  grabbed_.pending = true;
  simulator_.note_frame_captured();
  frame.timestamp_ns = simulator_.time_ns();
  frame.sequence = frames_++;
  frame.pan_rad = grabbed_.pan_rad;
  // Pairs come at a fixed cadence from the camera's start; a late capture gets the newest
  // pair and the next one comes at the next tick of the cadence (no bursts).
  const core::CameraConfig& camera = simulator_.camera_config();
  const auto period_ns = std::max<std::int64_t>(1, std::llround(1e9 / camera.frame_rate_hz));
  next_frame_ns_ = start_ns_ + ((simulator_.time_ns() - start_ns_) / period_ns + 1) * period_ns;
  return core::Status::success();
}

core::Status SimCamera::retrieve(core::StereoFrame& frame) { return render_grabbed(frame, nullptr); }

core::Status SimCamera::capture_with_depth(core::StereoFrame& frame, cv::Mat* depth_right) {
  const core::Status grabbed = grab(frame);
  return grabbed.ok() ? render_grabbed(frame, depth_right) : grabbed;
}

core::Status SimCamera::render_grabbed(core::StereoFrame& frame, cv::Mat* depth_right) {
  if (!grabbed_.pending) return {core::StatusCode::invalid_input, "no stereo pair grabbed to render"};
  const core::CameraConfig& camera = simulator_.camera_config();
  if (frame.left.rows != camera.height_px || frame.left.cols != camera.width_px || frame.left.type() != CV_8UC1 ||
      frame.right.rows != camera.height_px || frame.right.cols != camera.width_px || frame.right.type() != CV_8UC1) {
    return {core::StatusCode::invalid_input, "frame images not allocated at the camera size"};
  }
  renderer_.render(grabbed_.true_pose, grabbed_.pan_rad, grabbed_.time_s, grabbed_.frame_index, frame.left,
                   frame.right, depth_right);
  grabbed_.pending = false;
  ++rendered_;
  return core::Status::success();
}

core::Status SimOdometry::read(core::OdometryReading& reading) {
  OdometrySample sample;
  if (!simulator_.pop_odometry(sample)) return {core::StatusCode::not_available, "no new odometry reading"};
  reading = sample.reading;
  last_true_pose_ = sample.true_pose;
  return core::Status::success();
}

core::Status SimDrive::command(const core::DriveCommand& command) {
  simulator_.command(command);
  return core::Status::success();
}

core::Status SimDrive::stop() {
  simulator_.command(core::DriveCommand{});
  return core::Status::success();
}

void SimClock::sleep_until(std::int64_t deadline_ns) {
  simulator_.step_to(deadline_ns);
}

}  // namespace stereoscout::host_sim
