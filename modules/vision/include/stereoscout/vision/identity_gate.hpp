#pragma once
// Splits the descriptor index's identities by where their points lie (the odometry frame).
//
// The index names a landmark by its look alone, and a look can repeat: a floor's tiles, one
// texture tiled over several walls. One entry then takes the keys of every place that looks
// like it (the simulated office's first 300 s: 45% of re-observations lay elsewhere than
// their landmark, most more than a metre off; docs/results.md), and the filter weighs each
// such key as a re-observation of one landmark.
//
// The gate gives each index identity up to `instances_per_identity` *instances*, each a
// landmark of its own for the filter (ids 1, 2, ... in order of creation, never reused), with
// the point and covariance of its last sighting in the odometry frame. A key joins the
// instance of its identity whose last point agrees with its own within `gate_chi2`
// (Mahalanobis, both covariances plus the odometry's drift since that sighting, from the
// odometry error model's linear terms); a key near none of them starts a new instance. Over a
// short drive the odometry is exact to millimetres, so two places with one look a metre apart
// stay apart; over a long loop the drift widens the gate and a return to a place is still
// re-identified (and places of one look seen long ago merge again: off by default for that,
// docs/results.md). An identity with all its instances taken, or the instance pool full: the
// observation is dropped (counted). Everything is sized at construction.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Geometry>

#include "stereoscout/core/config/filter.hpp"
#include "stereoscout/core/config/vision.hpp"
#include "stereoscout/core/fixed_vector.hpp"
#include "stereoscout/core/geometry.hpp"
#include "stereoscout/core/messages.hpp"

namespace stereoscout::vision {

struct IdentityGateParams {
  std::size_t identities = 0;         // largest index identity (the index's capacity)
  std::size_t instances = 0;          // instances in all (the filter's landmarks)
  std::size_t instances_per_identity = 32;
  double gate_chi2 = 11.345;
  // The odometry's error, as the filter's proposal models it (linear terms).
  double translation_per_m = 0.05;
  double translation_per_rad = 0.01;
  double rotation_per_m = 0.02;
  double rotation_per_rad = 0.05;
};

// The gate of vision.identity_gate*: the index's capacity, the filter's association gate and
// its proposal's linear terms.
IdentityGateParams identity_gate_params_from_config(const core::VisionConfig& vision, const core::FilterConfig& filter);

// The largest landmark id the filter can be handed: the index's capacity, or with the gate on
// the gate's instances.
std::size_t landmark_id_capacity(const core::VisionConfig& vision);

struct IdentityGateStats {
  std::uint64_t observations = 0;       // keys handed in
  std::uint64_t joined = 0;             // joined an existing instance
  std::uint64_t instances_created = 0;  // started a new one (the first sighting of an identity too)
  std::uint64_t split = 0;              // of those, identities that already had an instance
  std::uint64_t dropped_identity_full = 0;
  std::uint64_t dropped_pool_full = 0;
  std::uint64_t dropped_unknown_identity = 0;  // 0 or past `identities`
};

class IdentityGate {
 public:
  explicit IdentityGate(const IdentityGateParams& params);

  // One frame's observations (index identities, camera optical frame), seen from the camera at
  // `odometry_from_camera` when the robot's odometry pose was `odometry`. Rewrites each
  // identity to its instance's; removes the dropped ones (order kept).
  void apply(const core::Pose2& odometry, const Eigen::Isometry3d& odometry_from_camera,
             core::FixedVector<core::LandmarkObservation>& observations);

  const IdentityGateStats& stats() const { return stats_; }
  std::size_t instances_used() const { return instances_.size(); }

 private:
  static constexpr std::uint32_t kNone = 0xFFFFFFFFU;
  struct Instance {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();  // odometry frame, last sighting
    Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
    double odometer_m = 0.0;    // distance and rotation driven at that sighting
    double odometer_rad = 0.0;
    std::uint32_t next = kNone;  // the identity's next instance
  };
  void advance_odometer(const core::Pose2& odometry);
  double drift_variance(const Instance& instance, double range_m) const;
  std::uint32_t nearest_instance(std::uint32_t identity, const Eigen::Vector3d& point, const Eigen::Matrix3d& covariance,
                                 double range_m, std::size_t& count) const;
  // The instance for one observation (its filter id - 1), or kNone when it is dropped.
  std::uint32_t place(std::uint32_t identity, const Eigen::Vector3d& point, const Eigen::Matrix3d& covariance,
                      double range_m);

  IdentityGateParams params_;
  std::vector<std::uint32_t> first_instance_;  // per index identity - 1
  core::FixedVector<Instance> instances_;       // instance id - 1
  core::Pose2 last_odometry_;
  bool has_odometry_ = false;
  double odometer_m_ = 0.0;
  double odometer_rad_ = 0.0;
  IdentityGateStats stats_;
};

}  // namespace stereoscout::vision
