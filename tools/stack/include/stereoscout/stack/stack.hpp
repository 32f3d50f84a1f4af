#pragma once
// The whole onboard stack: the static tick table of design.md section 3 over the platform
// interfaces. The same object runs in the simulator (host_sim), on a recorded log
// (host_replay) and on the robot (robot_pc); only the Board differs.
//
//   Stack stack(config, options, board, stopwatch);           // allocates everything
//   if (!stack.start(error)) ...                               // waits for the first odometry
//   while (stack.tick()) {}                                    // one scheduler pass + sleep
//   stack.finish();                                            // closes the sensor log
//
// Data flow of one observation (paper section II): the capture task keeps a stereo pair when
// the camera moved more than robot.update_min_translation_m / update_min_rotation_deg since
// the last kept pair (body or pan unit) and no kept pair is waiting; the observation update
// waits for the first odometry reading at or after the pair's time, interpolates the
// odometry pose to that time, runs the vision front end (landmarks, their ids split by place
// with vision.identity_gate, and the 2.5D scan) and the particle filter, and stores the scan
// for the just-in-time grid; the grid roll-up brings the estimate's grid forward (the
// particle the stack follows: the ML particle, or with filter.estimate_lineage_margin the one
// that keeps the lineage) and classifies it for the explorer; the replan and drive tasks step
// the explorer with the estimate's pose dead-reckoned forward by the odometry since the update.
//
// Everything the stack consumes goes to the sensor log in the order it was read (one
// ordered staging queue drained by the logging task), so that a replay sees each record at
// the same tick as the live run and reproduces it exactly.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/core/logging.hpp"
#include "stereoscout/core/ring_buffer.hpp"
#include "stereoscout/core/system_config.hpp"
#include "stereoscout/core/worker.hpp"
#include "stereoscout/explore/explorer.hpp"
#include "stereoscout/log/records.hpp"
#include "stereoscout/log/writer.hpp"
#include "stereoscout/occupancy/just_in_time_grid.hpp"
#include "stereoscout/occupancy/scan_archive.hpp"
#include "stereoscout/platform/camera.hpp"
#include "stereoscout/platform/clock.hpp"
#include "stereoscout/platform/drive.hpp"
#include "stereoscout/platform/gpio.hpp"
#include "stereoscout/platform/odometry.hpp"
#include "stereoscout/scheduler/scheduler.hpp"
#include "stereoscout/slam/particle_filter.hpp"
#include "stereoscout/stack/odometry_history.hpp"
#include "stereoscout/vision/front_end.hpp"
#include "stereoscout/vision/identity_check.hpp"
#include "stereoscout/vision/identity_gate.hpp"

namespace stereoscout::stack {

// The true pose, where one is known (the simulator; a replayed simulator log).
class GroundTruthSource {
 public:
  virtual ~GroundTruthSource() = default;
  // The true pose at `timestamp_ns` (the time of the frame just captured); false if unknown.
  virtual bool pose_at(std::int64_t timestamp_ns, core::Pose2& pose) = 0;
};

struct Board {
  platform::Camera* camera = nullptr;
  platform::Odometry* odometry = nullptr;
  platform::Drive* drive = nullptr;
  platform::Gpio* gpio = nullptr;
  platform::Clock* clock = nullptr;
  GroundTruthSource* ground_truth = nullptr;  // optional
  log::LogWriter* log = nullptr;              // optional: record the sensor log
};

// The explorer's view of classified grid cells: the occupancy module's CellState codes read
// as the explorer's bytes (the two enums have the same values, checked at compile time).
explore::GridView navigation_view(const occupancy::GridGeometry& geometry, const occupancy::CellState* cells,
                                  const std::uint8_t* in_view, const std::uint8_t* looked_over = nullptr);

enum class Localization : std::uint8_t { rbpf, groundtruth, odometry };
bool parse_localization(const std::string& text, Localization& localization);
const char* to_string(Localization localization);

enum class StopReason : std::uint8_t { running, explored, time_limit, log_ended, stopped };
const char* to_string(StopReason reason);

// One observation update, for the trajectory files: time, the odometry pose and (if known)
// the true pose interpolated to the pair's time.
struct UpdateRecord {
  std::int64_t timestamp_ns = 0;
  std::uint32_t update_index = 0;
  core::Pose2 odometry;
  core::Pose2 ground_truth;
  bool has_ground_truth = false;
};

struct StackCounters {
  std::uint64_t frames_captured = 0;      // pairs grabbed (Camera::grab)
  std::uint64_t frames_kept = 0;          // of them, retrieved (their images) for an update
  std::uint64_t frames_skipped_busy = 0;   // the camera moved but the last kept pair was still waiting
  std::uint64_t capture_failures = 0;      // timeout / io error from the camera (grab or retrieve)
  std::uint64_t frames_expired = 0;        // kept pair older than the odometry history: dropped
  std::uint64_t odometry_readings = 0;
  std::uint64_t odometry_rejected = 0;      // not finite, or not newer than the last: skipped
  std::uint64_t updates = 0;
  std::uint64_t updates_refused = 0;        // the filter refused (pool short): motion carried over
  std::uint64_t vision_failures = 0;
  std::uint64_t near_obstacle_columns = 0;  // scan columns taken from the stereo matches
  std::uint64_t rollups = 0;
  std::uint64_t replans = 0;              // explorer steps of the replan task
  std::uint64_t drive_commands = 0;       // commands sent to the drive (both explorer tasks)
  std::uint64_t emergency_stop_ticks = 0;
  std::uint64_t log_records_staged = 0;
  std::uint64_t log_stage_overflow = 0;     // staging queue full: record not logged
  std::uint64_t log_records_refused = 0;    // the writer refused (queue full on the robot)
  std::uint64_t ticks = 0;
  std::uint64_t heap_allocations_in_loop = 0;        // outside OpenCV's SIFT
  std::uint64_t heap_allocations_in_sift = 0;        // inside cv::SIFT (allocates per call)
};

struct StackOptions {
  Localization localization = Localization::rbpf;
  double max_time_s = 3600.0;           // run.max_time_s (or --max-time)
  std::int64_t end_time_ns = -1;        // replay: stop at the live run's last tick
};

class Stack {
 public:
  // Allocates every buffer and builds the modules that do not need the start pose.
  Stack(const core::SystemConfig& config, const StackOptions& options, const Board& board,
        const core::TimeSource& stopwatch);
  ~Stack();
  Stack(const Stack&) = delete;
  Stack& operator=(const Stack&) = delete;

  // Waits (on the board's clock) for the first odometry reading, up to
  // `start_timeout_s`, then starts the filter, the grid and the scheduler at that pose.
  bool start(double start_timeout_s, std::string& error);
  // One scheduler pass and a sleep until the next task is due. False once the run is over.
  bool tick();
  // Ends the run at the next tick (Ctrl-C on the robot, a replayed log that ran out).
  void request_stop();
  // Stops the drive, closes the sensor log (end_of_run at the last tick's time).
  void finish();

  StopReason stop_reason() const { return stop_reason_; }
  std::int64_t now_ns() const { return board_.clock->now_ns(); }
  double time_s() const { return static_cast<double>(now_ns() - start_ns_) * 1e-9; }
  const StackCounters& counters() const { return counters_; }

  // The parts, for the run's outputs and report (not for the tick loop).
  const slam::ParticleFilter& filter() const { return *filter_; }
  const occupancy::JustInTimeGrid& grid() const { return *grid_; }
  const occupancy::ScanArchive& scan_archive() const { return *archive_; }
  const explore::Explorer& explorer() const { return *explorer_; }
  const explore::GridView& grid_view() const { return view_; }
  const vision::VisionFrontEnd& vision() const { return *vision_; }
  // The front end's identities checked against the true camera poses; null without a
  // ground-truth source (the robot).
  const vision::IdentityCheck* identity_check() const { return identity_check_.get(); }
  // Null unless vision.identity_gate is on.
  const vision::IdentityGate* identity_gate() const { return identity_gate_.get(); }
  const scheduler::Scheduler& scheduler() const { return *scheduler_; }
  const core::FixedVector<UpdateRecord>& update_records() const { return update_records_; }
  const core::FixedVector<core::Pose2>& odometry_path() const { return odometry_path_; }
  Localization localization() const { return options_.localization; }
  // Where the stack believes the robot is now (the estimate's pose moved on by the odometry since).
  core::Pose2 current_pose() const;
  std::size_t landmark_count() const;

 private:
  struct StagedRecord {
    log::RecordType type = log::RecordType::odometry;
    std::int64_t timestamp_ns = 0;
    core::OdometryReading odometry;
    core::DriveCommand drive;
    core::Pose2 pose;
    log::GpioEvent gpio;
  };

  static core::Status run_safety(void* self);
  static core::Status run_capture(void* self);
  static core::Status run_odometry(void* self);
  static core::Status run_observation_update(void* self);
  static core::Status run_grid_rollup(void* self);
  static core::Status run_replan(void* self);
  static core::Status run_drive(void* self);
  static core::Status run_logging(void* self);
  static void run_scan(void* self);

  core::Status safety();
  core::Status capture();
  core::Status odometry();
  core::Status observation_update();
  void start_scan();
  void finish_scan();
  void keep_seen_obstacles(std::int64_t frame_ns, double pan_rad);
  core::Status grid_rollup();
  core::Status replan();
  core::Status step_explorer(bool grid_updated);
  core::Status logging();

  void build_scheduler();
  bool read_odometry_into_history();
  bool camera_moved(const core::StereoFrame& frame) const;
  bool stage(const StagedRecord& record);
  void check_end();

  core::SystemConfig config_;
  StackOptions options_;
  Board board_;
  const core::TimeSource& stopwatch_;

  // Perception and estimation.
  std::unique_ptr<vision::VisionFrontEnd> vision_;
  std::unique_ptr<vision::IdentityGate> identity_gate_;
  std::unique_ptr<vision::IdentityCheck> identity_check_;
  core::CameraMount mount_;
  std::unique_ptr<slam::ParticleFilter> filter_;
  std::unique_ptr<occupancy::JustInTimeGrid> grid_;
  std::unique_ptr<occupancy::ScanArchive> archive_;  // the final map's scans that left grid_'s ring
  std::unique_ptr<explore::Explorer> explorer_;
  std::unique_ptr<scheduler::Scheduler> scheduler_;
  core::FixedVector<core::LandmarkObservation> observations_;
  core::FixedVector<slam::TrajectoryNodeHandle> live_nodes_;
  core::DepthScan scan_;
  slam::WallLineParams wall_params_;  // filter.manhattan_*: the scan's wall for the filter
  std::vector<Eigen::Vector2d> seen_obstacles_;  // sized once: the last scan's obstacles at camera height, map frame
  explore::SeenObstacles seen_;                    // the used part of it
  core::DepthScan seen_scan_;  // the last update's scan, for seen_ (scan_ is overwritten by a refused update too)
  std::vector<occupancy::CellState> cells_;  // the estimate's grid classified, the explorer's view
  std::vector<std::uint8_t> in_view_;        // its in-view marks, same layout
  std::vector<std::uint8_t> looked_over_;    // its looked-over marks (empty: grid.looked_over_range_m 0)
  explore::GridView view_;

  // Sensors.
  core::StereoFrame capture_frame_;
  core::StereoFrame kept_frame_;
  bool frame_waiting_ = false;       // kept, not yet used by an update
  bool frame_unlogged_ = false;      // kept, not yet handed to the log
  bool frame_has_truth_ = false;
  core::Pose2 frame_truth_;
  OdometryHistory odometry_history_;
  core::Pose2 last_kept_odometry_;
  double last_kept_camera_heading_ = 0.0;
  bool kept_any_ = false;
  double pan_rad_ = 0.0;             // pan angle of the newest kept pair

  // Estimate.
  core::Pose2 pose_at_update_;       // the estimate's pose at the last update
  core::Pose2 odometry_at_update_;   // odometry pose (interpolated) at the last update
  bool rollup_due_ = false;
  bool grid_changed_ = false;
  core::FixedVector<UpdateRecord> update_records_;
  core::FixedVector<core::Pose2> odometry_path_;  // every odometry reading (for map.png)

  // Safety and output.
  bool emergency_stop_ = false;
  bool emergency_stop_logged_ = false;
  bool motor_enabled_ = false;
  bool motor_enable_known_ = false;

  core::RingBuffer<StagedRecord> staged_;
  occupancy::CellThresholds thresholds_;
  StackCounters counters_;
  std::int64_t start_ns_ = 0;
  StopReason stop_reason_ = StopReason::running;
  bool started_ = false;
  bool finished_ = false;

  // vision.scan_parallel: the kept pair's dense scan runs here while the update goes on. Last,
  // so that it is destroyed (its job waited for) before what the job uses.
  std::unique_ptr<core::Worker> scan_worker_;
  core::Status scan_status_;   // written by the scan's job
  bool scan_pending_ = false;  // started, not yet finished
};

}  // namespace stereoscout::stack
