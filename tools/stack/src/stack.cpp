#include "stereoscout/stack/stack.hpp"

#include <cmath>
#include <cstdio>
#include <utility>

#include "stereoscout/core/allocation_counter.hpp"
#include "stereoscout/slam/observation_model.hpp"
#include "stereoscout/vision/calibration.hpp"

namespace stereoscout::stack {
namespace {

// 3 s of odometry at the paper's 5.4 Hz: a kept pair waits at most one update period for the
// reading after it, so this is room for a deferred update on an overloaded robot.
constexpr std::size_t kOdometryHistory = 16;
// Records staged between two runs of the logging task (at most a frame, its true pose, a
// few odometry readings, drive commands and gpio events): ample.
constexpr std::size_t kStagedRecords = 256;
// The identity check counts apart the identities first seen below this height: the floor's
// (the simulator's truth has z the height above the floor; stereo points on it scatter by
// centimetres).
constexpr double kFloorPoint_m = 0.05;
// How often start() polls for the first odometry reading.
constexpr std::int64_t kStartPollNs = 10'000'000;

// The filter for the ablations: one particle, no motion noise, no landmarks, so that its
// trajectory is exactly the pose source and the grid still hangs off its trajectory tree.
core::FilterConfig filter_config_for(const core::FilterConfig& config, Localization localization) {
  if (localization == Localization::rbpf) return config;
  core::FilterConfig single = config;
  single.particles = 1;
  single.particle_capacity = 1;
  single.motion_noise_translation_per_m = 0.0;
  single.motion_noise_rotation_per_rad = 0.0;
  single.motion_noise_rotation_per_m = 0.0;
  single.motion_noise_translation_per_rad = 0.0;
  single.landmark_node_capacity = 64;
  single.landmark_estimate_capacity = 64;
  single.manhattan_heading_sigma_deg = 0.0;  // one particle: nothing to weigh
  return single;
}

std::size_t records_for(double max_time_s, double rate_hz) {
  return static_cast<std::size_t>(std::ceil(max_time_s * rate_hz)) + 16;
}

}  // namespace

explore::GridView navigation_view(const occupancy::GridGeometry& geometry, const occupancy::CellState* cells,
                                  const std::uint8_t* in_view, const std::uint8_t* looked_over) {
  static_assert(sizeof(occupancy::CellState) == 1);
  static_assert(static_cast<int>(occupancy::CellState::unknown) == static_cast<int>(explore::CellState::unknown) &&
                static_cast<int>(occupancy::CellState::free) == static_cast<int>(explore::CellState::free) &&
                static_cast<int>(occupancy::CellState::occupied) == static_cast<int>(explore::CellState::occupied));
  explore::GridView view;
  view.width = geometry.width_cells;
  view.height = geometry.height_cells;
  view.resolution_m = geometry.resolution_m;
  view.origin_m = Eigen::Vector2d(geometry.origin_x_m, geometry.origin_y_m);
  view.cells = reinterpret_cast<const std::uint8_t*>(cells);  // unsigned char may alias any object
  view.in_view = in_view;
  view.looked_over = looked_over;
  return view;
}

bool parse_localization(const std::string& text, Localization& localization) {
  if (text == "rbpf") localization = Localization::rbpf;
  else if (text == "groundtruth") localization = Localization::groundtruth;
  else if (text == "odometry") localization = Localization::odometry;
  else return false;
  return true;
}

const char* to_string(Localization localization) {
  switch (localization) {
    case Localization::rbpf: return "rbpf";
    case Localization::groundtruth: return "groundtruth";
    case Localization::odometry: return "odometry";
  }
  return "unknown";
}

const char* to_string(StopReason reason) {
  switch (reason) {
    case StopReason::running: return "running";
    case StopReason::explored: return "explored";
    case StopReason::time_limit: return "time_limit";
    case StopReason::log_ended: return "log_ended";
    case StopReason::stopped: return "stopped";
  }
  return "unknown";
}

Stack::Stack(const core::SystemConfig& config, const StackOptions& options, const Board& board,
             const core::TimeSource& stopwatch)
    : config_(config),
      options_(options),
      board_(board),
      stopwatch_(stopwatch),
      observations_(static_cast<std::size_t>(config.vision.max_features)),
      live_nodes_(static_cast<std::size_t>(filter_config_for(config.filter, options.localization).particle_capacity) + 1),
      seen_obstacles_(static_cast<std::size_t>(config.camera.width_px)),
      odometry_history_(kOdometryHistory),
      update_records_(records_for(options.max_time_s, config.budgets.tasks[3].rate_hz)),
      odometry_path_(records_for(options.max_time_s, config.robot.odometry_rate_hz)),
      staged_(kStagedRecords),
      thresholds_(occupancy::CellThresholds::from_config(config.grid)) {
  mount_ = slam::camera_mount_from_config(config.camera);
  vision_ = std::make_unique<vision::VisionFrontEnd>(config.vision, config.robot,
                                                     vision::calibration_from_config(config.camera), mount_);
  if (config.vision.identity_gate) {
    identity_gate_ = std::make_unique<vision::IdentityGate>(vision::identity_gate_params_from_config(config.vision, config.filter));
  }
  if (board.ground_truth != nullptr) {
    identity_check_ = std::make_unique<vision::IdentityCheck>(vision::landmark_id_capacity(config.vision),
                                                              config.filter.association_gate_chi2, kFloorPoint_m);
  }
  vision_->allocate_scan(scan_);
  vision_->allocate_scan(seen_scan_);
  if (config.vision.scan_parallel) scan_worker_ = std::make_unique<core::Worker>();
  wall_params_ = slam::wall_line_params_from_config(config.filter);
  const slam::StereoModel stereo = slam::stereo_model_from_config(config.camera, config.vision);
  filter_ = std::make_unique<slam::ParticleFilter>(filter_config_for(config.filter, options.localization), mount_,
                                                   static_cast<std::uint64_t>(config.run.seed), &stereo);
  capture_frame_.allocate(config.camera.width_px, config.camera.height_px);
  kept_frame_.allocate(config.camera.width_px, config.camera.height_px);
  core::ExploreConfig explore = config.explore;
  explore.time_limit_s = std::min(explore.time_limit_s, options.max_time_s);
  explorer_ = std::make_unique<explore::Explorer>(explore::ExploreParams::from_config(
      explore, config.robot, config.camera, config.vision, config.grid.width_cells, config.grid.height_cells));
  cells_.assign(static_cast<std::size_t>(config.grid.width_cells) * static_cast<std::size_t>(config.grid.height_cells),
                occupancy::CellState::unknown);
  in_view_.assign(cells_.size(), 0);
  if (config.grid.looked_over_range_m > 0.0) looked_over_.assign(cells_.size(), 0);
}

Stack::~Stack() {
  finish();
  // Both release their trajectory nodes while the filter's tree exists (also the member order).
  archive_.reset();
  grid_.reset();
}

bool Stack::start(double start_timeout_s, std::string& error) {
  start_ns_ = board_.clock->now_ns();
  if (board_.log != nullptr) {
    board_.log->write_run_info(start_ns_, log::RunInfo{static_cast<std::uint64_t>(config_.run.seed),
                                                       static_cast<std::uint32_t>(options_.localization),
                                                       STEREOSCOUT_VERSION});
    board_.log->write_config(start_ns_, core::to_yaml(config_));
  }
  const auto deadline_ns = start_ns_ + static_cast<std::int64_t>(start_timeout_s * 1e9);
  while (!read_odometry_into_history()) {
    if (board_.clock->now_ns() >= deadline_ns) {
      char text[96];
      std::snprintf(text, sizeof text, "no odometry reading within %.1f s of start", start_timeout_s);
      error = text;
      return false;
    }
    board_.clock->sleep_until(board_.clock->now_ns() + kStartPollNs);
  }
  logging();
  const core::OdometryReading& first = odometry_history_.newest();
  filter_->start(first, first.pose);
  const occupancy::GridGeometry geometry = occupancy::GridGeometry::centred_on(config_.grid, first.pose);
  grid_ = std::make_unique<occupancy::JustInTimeGrid>(config_.grid, geometry,
                                                      static_cast<std::size_t>(config_.camera.width_px),
                                                      filter_->trajectory());
  archive_ = std::make_unique<occupancy::ScanArchive>(
      geometry, config_.grid.final_map_resolution_m, config_.grid.final_map_tile_m,
      static_cast<std::size_t>(config_.grid.final_map_archive_tiles), occupancy::LogOddsModel::from_config(config_.grid),
      filter_->trajectory());
  view_ = navigation_view(geometry, cells_.data(), in_view_.data(), looked_over_.empty() ? nullptr : looked_over_.data());
  pose_at_update_ = filter_->estimate_pose();
  odometry_at_update_ = first.pose;
  rollup_due_ = true;  // the root gets a grid, so every lineage has one above it
  grid_rollup();
  build_scheduler();
  started_ = true;
  return true;
}

void Stack::build_scheduler() {
  using Run = core::Status (*)(void*);
  const Run runs[core::BudgetsConfig::kTaskCount] = {&Stack::run_safety,        &Stack::run_capture,
                                                      &Stack::run_odometry,      &Stack::run_observation_update,
                                                      &Stack::run_grid_rollup,   &Stack::run_replan,
                                                      &Stack::run_drive,         &Stack::run_logging};
  // Design.md section 3: the observation update, the grid roll-up and replanning may wait
  // when the loop is behind; safety, capture, odometry, drive and logging never do.
  const bool deferrable[core::BudgetsConfig::kTaskCount] = {false, false, false, true, true, true, false, false};
  scheduler::TaskSpec table[core::BudgetsConfig::kTaskCount];
  for (std::size_t i = 0; i < core::BudgetsConfig::kTaskCount; ++i) {
    table[i].name = core::BudgetsConfig::kTaskNames[i];
    table[i].rate_hz = config_.budgets.tasks[i].rate_hz;
    table[i].budget_us = config_.budgets.tasks[i].budget_us;
    table[i].policy = deferrable[i] ? scheduler::OverloadPolicy::deferrable : scheduler::OverloadPolicy::never_skip;
    table[i].run = runs[i];
    table[i].context = this;
  }
  scheduler_ = std::make_unique<scheduler::Scheduler>(table, core::BudgetsConfig::kTaskCount, *board_.clock, stopwatch_);
}

bool Stack::tick() {
  if (!started_ || stop_reason_ != StopReason::running) return false;
  std::int64_t next_due_ns = 0;
  {
    const core::AllocationScope scope;
    const std::uint64_t in_sift_before = counters_.heap_allocations_in_sift;
    next_due_ns = scheduler_->run_due();
    counters_.heap_allocations_in_loop += scope.allocations() - (counters_.heap_allocations_in_sift - in_sift_before);
  }
  ++counters_.ticks;
  check_end();
  if (stop_reason_ != StopReason::running) return false;
  board_.clock->sleep_until(next_due_ns);
  return true;
}

void Stack::request_stop() {
  if (stop_reason_ == StopReason::running) stop_reason_ = StopReason::stopped;
}

void Stack::check_end() {
  if (stop_reason_ != StopReason::running) return;
  if (explorer_->state() == explore::ExploreState::finished) {
    stop_reason_ = StopReason::explored;
  } else if (options_.end_time_ns >= 0 && now_ns() >= options_.end_time_ns) {
    stop_reason_ = StopReason::log_ended;
  } else if (time_s() >= options_.max_time_s) {
    stop_reason_ = StopReason::time_limit;
  }
}

void Stack::finish() {
  if (finished_) return;
  finished_ = true;
  if (board_.drive != nullptr) board_.drive->stop();
  if (board_.log != nullptr) {
    logging();
    board_.log->close(board_.clock->now_ns());
  }
}

core::Pose2 Stack::current_pose() const {
  if (odometry_history_.empty()) return pose_at_update_;
  return pose_at_update_.compose(odometry_at_update_.between(odometry_history_.newest().pose));
}

// ---- tasks -------------------------------------------------------------------------------

core::Status Stack::run_safety(void* self) { return static_cast<Stack*>(self)->safety(); }
core::Status Stack::run_capture(void* self) { return static_cast<Stack*>(self)->capture(); }
core::Status Stack::run_odometry(void* self) { return static_cast<Stack*>(self)->odometry(); }
core::Status Stack::run_observation_update(void* self) { return static_cast<Stack*>(self)->observation_update(); }
core::Status Stack::run_grid_rollup(void* self) { return static_cast<Stack*>(self)->grid_rollup(); }
core::Status Stack::run_replan(void* self) { return static_cast<Stack*>(self)->replan(); }
core::Status Stack::run_drive(void* self) { return static_cast<Stack*>(self)->step_explorer(false); }
core::Status Stack::run_logging(void* self) { return static_cast<Stack*>(self)->logging(); }

core::Status Stack::safety() {
  const bool active = board_.gpio->emergency_stop_active();
  if (active != emergency_stop_ || !emergency_stop_logged_) {
    StagedRecord record;
    record.type = log::RecordType::gpio_event;
    record.timestamp_ns = now_ns();
    record.gpio = log::GpioEvent{log::GpioEvent::emergency_stop, active};
    stage(record);
    emergency_stop_logged_ = true;
  }
  emergency_stop_ = active;
  if (active) {
    ++counters_.emergency_stop_ticks;
    board_.drive->stop();
  }
  // The motor enable line follows the e-stop, switched on change only.
  if (!motor_enable_known_ || motor_enabled_ == active) {
    motor_enabled_ = !active;
    motor_enable_known_ = true;
    return board_.gpio->set_motor_enable(motor_enabled_);
  }
  return core::Status::success();
}

// Every pair is grabbed (its time and pan angle); only a pair the stack keeps is retrieved
// (its images: the simulator renders them then).
core::Status Stack::capture() {
  const core::Status status = board_.camera->grab(capture_frame_);
  if (status.code == core::StatusCode::not_available) return core::Status::success();
  if (!status.ok()) {
    ++counters_.capture_failures;
    return status;
  }
  ++counters_.frames_captured;
  if (!camera_moved(capture_frame_)) return core::Status::success();
  if (frame_waiting_ || frame_unlogged_) {
    ++counters_.frames_skipped_busy;
    return core::Status::success();
  }
  const core::Status retrieved = board_.camera->retrieve(capture_frame_);
  if (!retrieved.ok()) {
    ++counters_.capture_failures;
    return retrieved;
  }
  std::swap(capture_frame_, kept_frame_);  // swaps image headers: no copy, no allocation
  ++counters_.frames_kept;
  frame_waiting_ = true;
  kept_any_ = true;
  pan_rad_ = kept_frame_.pan_rad;
  last_kept_odometry_ = odometry_history_.newest().pose;
  last_kept_camera_heading_ = last_kept_odometry_.theta + kept_frame_.pan_rad;
  frame_has_truth_ = board_.ground_truth != nullptr && board_.ground_truth->pose_at(kept_frame_.timestamp_ns, frame_truth_);
  if (board_.log != nullptr) {
    StagedRecord record;
    record.type = log::RecordType::stereo_frame;
    record.timestamp_ns = kept_frame_.timestamp_ns;
    frame_unlogged_ = stage(record);
    if (frame_has_truth_) {
      record.type = log::RecordType::ground_truth;
      record.pose = frame_truth_;
      stage(record);
    }
  }
  return core::Status::success();
}

// Paper II: an observation update when the robot moved more than 7 cm or the camera turned
// more than 1 degree (body or pan unit) since the last one.
bool Stack::camera_moved(const core::StereoFrame& frame) const {
  if (!kept_any_) return true;
  const core::Pose2& odometry = odometry_history_.newest().pose;
  const double moved_m = (odometry.translation() - last_kept_odometry_.translation()).norm();
  const double turned_rad = std::abs(core::wrap_angle(odometry.theta + frame.pan_rad - last_kept_camera_heading_));
  return moved_m > config_.robot.update_min_translation_m ||
         turned_rad > core::degrees_to_radians(config_.robot.update_min_rotation_deg);
}

core::Status Stack::odometry() {
  read_odometry_into_history();
  return core::Status::success();
}

bool Stack::read_odometry_into_history() {
  bool any = false;
  core::OdometryReading reading;
  while (board_.odometry->read(reading).ok()) {
    const bool finite = std::isfinite(reading.pose.x) && std::isfinite(reading.pose.y) && std::isfinite(reading.pose.theta);
    if (!finite || !odometry_history_.add(reading)) {
      ++counters_.odometry_rejected;
      continue;
    }
    any = true;
    ++counters_.odometry_readings;
    odometry_path_.push_back(reading.pose);
    StagedRecord record;
    record.type = log::RecordType::odometry;
    record.timestamp_ns = reading.timestamp_ns;
    record.odometry = reading;
    stage(record);
  }
  return any;
}

core::Status Stack::observation_update() {
  if (!frame_waiting_) return core::Status::success();
  const std::int64_t frame_ns = kept_frame_.timestamp_ns;
  if (odometry_history_.newest().timestamp_ns < frame_ns) return core::Status::success();  // wait for the reading after it
  frame_waiting_ = false;
  core::OdometryReading at_frame;
  at_frame.timestamp_ns = frame_ns;
  at_frame.sequence = odometry_history_.newest().sequence;
  if (!odometry_history_.pose_at(frame_ns, at_frame.pose)) {
    ++counters_.frames_expired;
    return {core::StatusCode::not_available, "kept pair older than the odometry history"};
  }
  const core::Pose2 odometry_at_frame = at_frame.pose;
  if (options_.localization == Localization::groundtruth) {
    if (!frame_has_truth_) return {core::StatusCode::invalid_input, "no ground truth for the kept pair"};
    at_frame.pose = frame_truth_;
  }
  observations_.clear();
  if (options_.localization == Localization::rbpf) {
    const core::AllocationScope sift_scope;
    const core::Status seen = vision_->observe_landmarks(kept_frame_, observations_);
    counters_.heap_allocations_in_sift += sift_scope.allocations();
    if (!seen.ok()) ++counters_.vision_failures;
    const Eigen::Isometry3d robot_from_camera = core::robot_from_camera(mount_, kept_frame_.pan_rad);
    if (identity_gate_) {
      identity_gate_->apply(odometry_at_frame, odometry_at_frame.to_isometry3() * robot_from_camera, observations_);
    }
    if (identity_check_ && frame_has_truth_) {
      identity_check_->observe(frame_truth_.to_isometry3() * robot_from_camera, observations_.data(),
                               observations_.size());
    }
  }
  start_scan();  // beside the filter update, once SIFT's two threads are done; finished before any return
  slam::WallLine wall;
  const bool use_wall = filter_->config().manhattan_heading_sigma_deg > 0.0;
  if (use_wall) finish_scan();  // the filter needs the scan's wall
  const bool wall_seen = use_wall && slam::fit_wall_line(scan_, wall_params_, wall);
  const slam::UpdateResult result = filter_->update(
      at_frame, slam::ObservationList{observations_.data(), observations_.size()}, kept_frame_.pan_rad,
      wall_seen ? &wall : nullptr);
  finish_scan();
  if (!result.status.ok()) {
    ++counters_.updates_refused;  // the filter carries the motion over to the next update
    return result.status;
  }
  const std::uint32_t index = filter_->trajectory().get(filter_->ml_trajectory_node()).update_index;
  archive_->keep_leaving_scan(grid_->scans(), index, filter_->ml_trajectory_node());
  grid_->record_scan(index, scan_);
  pose_at_update_ = filter_->estimate_pose();
  odometry_at_update_ = odometry_at_frame;
  keep_seen_obstacles(frame_ns, kept_frame_.pan_rad);
  update_records_.push_back(UpdateRecord{frame_ns, index, odometry_at_frame, frame_truth_, frame_has_truth_});
  rollup_due_ = true;
  ++counters_.updates;
  return core::Status::success();
}

// The kept pair's dense disparity and scan, on the scan worker while the filter update runs
// (it touches neither scan_ nor the front end's dense matcher, and the stereo matches the scan
// reads stay as observe_landmarks left them until the next pair), or here.
void Stack::start_scan() {
  scan_pending_ = true;
  if (scan_worker_) {
    scan_worker_->start(&Stack::run_scan, this);
  } else {
    run_scan(this);
  }
}

void Stack::run_scan(void* self) {
  auto* stack = static_cast<Stack*>(self);
  stack->scan_status_ = stack->vision_->scan(stack->kept_frame_, stack->scan_);
}

// Waits for the scan started last and counts its failure, once.
void Stack::finish_scan() {
  if (!scan_pending_) return;
  if (scan_worker_) scan_worker_->wait();
  scan_pending_ = false;
  if (scan_status_.ok()) {
    counters_.near_obstacle_columns += vision_->last_near_columns();
  } else {
    ++counters_.vision_failures;
  }
}

// The scan's obstacles at the camera's height, placed with the pose the grid uses for this
// scan, for the explorer's safety check (explore::SeenObstacles).
void Stack::keep_seen_obstacles(std::int64_t frame_ns, double pan_rad) {
  seen_.points = seen_obstacles_.data();
  seen_.count = explore::seen_obstacles_from_scan(scan_, pose_at_update_, seen_obstacles_.data(), seen_obstacles_.size());
  seen_.time_s = static_cast<double>(frame_ns - start_ns_) * 1e-9;
  seen_scan_ = scan_;  // same column count: no allocation
  seen_.scan = &seen_scan_;
  seen_.odometry = odometry_at_update_;
  seen_.pose = pose_at_update_;
  seen_.pan_rad = pan_rad;
}

core::Status Stack::grid_rollup() {
  if (!rollup_due_) return core::Status::success();
  rollup_due_ = false;
  live_nodes_.clear();
  for (std::size_t i = 0; i < filter_->particle_count(); ++i) live_nodes_.push_back(filter_->particle(i).trajectory);
  live_nodes_.push_back(filter_->estimate_node());  // resampling may have left no particle on it
  grid_->update(filter_->estimate_node(), live_nodes_.data(), live_nodes_.size());
  if (const occupancy::OccupancyGrid* grid = grid_->ml_grid()) {
    occupancy::classify_cells(*grid, thresholds_, cells_.data(), in_view_.data(),
                              looked_over_.empty() ? nullptr : looked_over_.data());
  }
  grid_changed_ = true;
  ++counters_.rollups;
  return core::Status::success();
}

core::Status Stack::replan() {
  ++counters_.replans;
  const bool updated = grid_changed_;
  grid_changed_ = false;
  return step_explorer(updated);
}

core::Status Stack::step_explorer(bool grid_updated) {
  explore::ExploreInput input;
  input.time_s = time_s();
  input.pose = current_pose();
  input.odometry = odometry_history_.empty() ? odometry_at_update_ : odometry_history_.newest().pose;
  input.pan_rad = pan_rad_;
  input.grid = view_;
  input.seen = seen_;
  input.grid_updated = grid_updated;
  input.emergency_stop = emergency_stop_;
  const explore::ExploreOutput output = explorer_->step(input);
  board_.camera->command_pan(output.pan_target_rad);
  const core::DriveCommand command = emergency_stop_ ? core::DriveCommand{} : output.drive;
  const core::Status status = emergency_stop_ ? board_.drive->stop() : board_.drive->command(command);
  ++counters_.drive_commands;
  StagedRecord record;
  record.type = log::RecordType::drive_command;
  record.timestamp_ns = now_ns();
  record.drive = command;
  stage(record);
  return status;
}

bool Stack::stage(const StagedRecord& record) {
  if (board_.log == nullptr) return false;
  if (!staged_.try_push(record)) {
    ++counters_.log_stage_overflow;
    return false;
  }
  ++counters_.log_records_staged;
  return true;
}

// Hands the staged records to the log writer in the order they were read, which is the
// order a replay must see them in.
core::Status Stack::logging() {
  if (board_.log == nullptr) return core::Status::success();
  while (!staged_.empty()) {
    const StagedRecord& record = staged_.front();
    bool written = false;
    switch (record.type) {
      case log::RecordType::stereo_frame:
        written = board_.log->write_stereo_frame(kept_frame_);
        frame_unlogged_ = false;
        break;
      case log::RecordType::ground_truth: written = board_.log->write_ground_truth(record.timestamp_ns, record.pose); break;
      case log::RecordType::odometry: written = board_.log->write_odometry(record.odometry); break;
      case log::RecordType::drive_command:
        written = board_.log->write_drive_command(record.timestamp_ns, record.drive);
        break;
      case log::RecordType::gpio_event: written = board_.log->write_gpio_event(record.timestamp_ns, record.gpio); break;
      default: break;
    }
    if (!written) ++counters_.log_records_refused;
    staged_.pop_front();
  }
  return core::Status::success();
}

std::size_t Stack::landmark_count() const { return vision_->index().stats().landmarks; }

}  // namespace stereoscout::stack
