#pragma once
// Are the front end's landmark identities right? An evaluation against the true camera poses
// (the simulator, a dataset's ground truth), independent of any filter.
//
// Every identity keeps its stereo points fused in the world frame by the true camera poses:
// the estimate a filter would store with a perfect trajectory. A re-observation is consistent
// when that stored estimate, moved into the current camera by the true motion, agrees with the
// new stereo point within the sum of both covariances (chi-square gate); only consistent
// sightings are fused, so one wrong re-identification does not move the stored point.
//
// Storage is one slot per identity, sized at construction (identities 1..capacity, which the
// descriptor index never exceeds: its landmarks are never evicted); nothing allocates later.
// An identity past the capacity is counted, not checked.
//
// Where the world frame's z is the height above a floor (the simulator), the re-observations of
// identities first seen on the floor (below `floor_below_m`) are also counted apart: a floor's
// tiles repeat in reality too, and the split tells that from the rest of the scene.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "stereoscout/core/messages.hpp"

namespace stereoscout::vision {

class IdentityCheck {
 public:
  // floor_below_m: NaN (the default) where the world frame's z is not a height (a dataset's
  // first camera frame).
  IdentityCheck(std::size_t capacity, double gate_chi2, double floor_below_m = kNoFloor);
  static constexpr double kNoFloor = std::numeric_limits<double>::quiet_NaN();

  // All observations of one frame, in the optical frame of the camera at `world_from_camera`.
  void observe(const Eigen::Isometry3d& world_from_camera, const core::LandmarkObservation* observations,
               std::size_t count);

  std::uint64_t first_sightings() const { return first_sightings_; }
  std::uint64_t reobservations() const { return reobservations_; }
  std::uint64_t consistent() const { return consistent_; }
  std::uint64_t past_capacity() const { return past_capacity_; }
  // Of reobservations() and consistent(): those of identities first seen on the floor.
  std::uint64_t floor_reobservations() const { return floor_reobservations_; }
  std::uint64_t floor_consistent() const { return floor_consistent_; }
  // Share of re-observations that were consistent (0 before any).
  double consistency() const {
    return reobservations_ == 0 ? 0.0 : static_cast<double>(consistent_) / static_cast<double>(reobservations_);
  }

 private:
  struct Stored {
    Eigen::Vector3d mean_world = Eigen::Vector3d::Zero();
    Eigen::Matrix3d covariance_world = Eigen::Matrix3d::Zero();
    bool seen = false;
    bool on_floor = false;
  };
  double gate_chi2_;
  double floor_below_m_;
  std::vector<Stored> stored_;  // index: identity - 1
  std::uint64_t first_sightings_ = 0;
  std::uint64_t reobservations_ = 0;
  std::uint64_t consistent_ = 0;
  std::uint64_t past_capacity_ = 0;
  std::uint64_t floor_reobservations_ = 0;
  std::uint64_t floor_consistent_ = 0;
};

}  // namespace stereoscout::vision
