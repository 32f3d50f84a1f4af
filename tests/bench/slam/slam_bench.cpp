// Speed and memory of the RBPF observation update (paper III: the FastSLAM tree makes an
// update O(N log K) instead of O(N K)).
//
// BM_ObservationUpdate/N/K: one update of N particles with 200 observations, every particle
//   starting from one shared map of K landmarks (the state right after the particles
//   coalesce, the most copying an update can need). Counters: nodes and bytes the shared
//   trees hold after the update, next to the bytes N private copies of the map would hold.
// BM_CopyWholeMapResample/N/K: the baseline without sharing, written only here: resampling
//   copies each particle's whole map (a flat array of K estimates), as a naive RBPF must.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "stereoscout/core/random.hpp"
#include "stereoscout/slam/particle_filter.hpp"

namespace stereoscout::slam {
namespace {

constexpr std::size_t kObservationsPerUpdate = 200;

Eigen::Vector3d landmark_position(std::uint32_t id) {
  // Landmarks spread over a 40 m x 40 m x 2 m volume, deterministic.
  core::RandomStream stream(3, {core::stream_purpose::test, id, 0});
  return Eigen::Vector3d(stream.uniform(-20.0, 20.0), stream.uniform(-20.0, 20.0), stream.uniform(0.0, 2.0));
}

// Nodes one particle copies when its 200 observations hit distinct leaves of a depth-d tree:
// the level l below the root holds at most min(8^l, 200) distinct path nodes.
std::size_t path_nodes_per_update(std::size_t landmarks) {
  const unsigned depth = levels_for_id(static_cast<std::uint32_t>(landmarks - 1));
  std::size_t nodes = 0;
  std::size_t level_width = 1;
  for (unsigned level = 0; level <= depth; ++level) {
    nodes += std::min<std::size_t>(level_width, kObservationsPerUpdate);
    level_width = std::min<std::size_t>(level_width * kTrieFanout, kObservationsPerUpdate);
  }
  return nodes;
}

struct Scenario {
  std::vector<PriorLandmark> prior;
  std::vector<core::LandmarkObservation> observations;
};

Scenario make_scenario(std::size_t landmarks, std::uint32_t draw = 0) {
  Scenario scenario;
  for (std::uint32_t id = 0; id < landmarks; ++id) {
    PriorLandmark p;
    p.landmark_id = id;
    p.estimate.mean = landmark_position(id);
    p.estimate.covariance = Eigen::Matrix3d::Identity() * 0.02;
    p.estimate.observations = 4;
    scenario.prior.push_back(p);
  }
  core::RandomStream pick(5, {core::stream_purpose::test, draw, 1});
  std::vector<std::uint32_t> ids(landmarks);
  for (std::uint32_t id = 0; id < landmarks; ++id) {
    ids[id] = id;
  }
  for (std::size_t k = 0; k < kObservationsPerUpdate; ++k) {  // partial Fisher-Yates: distinct ids
    const std::size_t j = k + pick.uniform_index(static_cast<std::uint32_t>(landmarks - k));
    std::swap(ids[k], ids[j]);
    core::LandmarkObservation o;
    o.landmark_id = ids[k];
    o.point_camera = landmark_position(ids[k]) + Eigen::Vector3d(pick.gaussian(0.0, 0.05), pick.gaussian(0.0, 0.05), 0.0);
    o.covariance = Eigen::Matrix3d::Identity() * 0.01;
    scenario.observations.push_back(o);
  }
  return scenario;
}

void BM_ObservationUpdate(benchmark::State& state) {
  const auto particles = static_cast<std::size_t>(state.range(0));
  const auto landmarks = static_cast<std::size_t>(state.range(1));
  const Scenario scenario = make_scenario(landmarks);
  core::FilterConfig config;
  config.particles = static_cast<int>(particles);
  config.particle_capacity = config.particles;
  config.landmark_node_capacity = static_cast<int>(2 * landmarks + particles * path_nodes_per_update(landmarks) + 1000);
  config.landmark_estimate_capacity = static_cast<int>(landmarks + particles * kObservationsPerUpdate + 1000);
  config.trajectory_node_capacity = static_cast<int>(3 * particles + 10);
  config.resample_ess_fraction = 0.0;  // measure the observation update itself
  ParticleFilter filter(config, core::CameraMount{}, 1);
  const ObservationList observations{scenario.observations.data(), scenario.observations.size()};
  std::size_t nodes_held = 0;
  std::size_t estimates_held = 0;
  // One untimed round first, so the pools' pages are mapped as on a robot that has run a while.
  filter.start(core::OdometryReading{}, {}, scenario.prior.data(), scenario.prior.size());
  filter.update(core::OdometryReading{1, 1, core::Pose2{0.05, 0.0, 0.01}}, observations, Eigen::Isometry3d::Identity());
  for (auto _ : state) {
    state.PauseTiming();
    filter.start(core::OdometryReading{}, {}, scenario.prior.data(), scenario.prior.size());
    state.ResumeTiming();
    filter.update(core::OdometryReading{1, 1, core::Pose2{0.05, 0.0, 0.01}}, observations, Eigen::Isometry3d::Identity());
    state.PauseTiming();
    nodes_held = filter.landmarks().nodes_in_use();
    estimates_held = filter.landmarks().estimates_in_use();
    state.ResumeTiming();
  }
  const double tree_bytes = static_cast<double>(nodes_held * sizeof(MapNode) + estimates_held * sizeof(LandmarkEstimate));
  state.counters["nodes_held"] = static_cast<double>(nodes_held);
  state.counters["estimates_held"] = static_cast<double>(estimates_held);
  state.counters["tree_MB"] = tree_bytes / 1e6;
  state.counters["copy_map_MB"] =
      static_cast<double>(particles * landmarks * sizeof(LandmarkEstimate)) / 1e6;  // N private maps
  state.counters["refused"] = static_cast<double>(filter.counters().changes_refused_pool_full);
}
BENCHMARK(BM_ObservationUpdate)
    ->ArgsProduct({{100, 1000, 2000, 5000}, {1000, 10000, 20000}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

// A run in progress: consecutive updates, each with 200 observations of a new random subset of
// the K landmarks, motion noise on and systematic resampling whenever ESS < N / 2, starting from
// one shared map. The time is for all 10 updates; counters: what the trees hold at the end.
// linearised: filter.linearise_at_estimate (0 off; 1 compares each observation with the
// estimate through the stereo model, the sensor then a camera 10 m below the floor looking up,
// so that every landmark is in front of it and takes that path).
void BM_ConsecutiveUpdates(benchmark::State& state) {
  const auto particles = static_cast<std::size_t>(state.range(0));
  const auto landmarks = static_cast<std::size_t>(state.range(1));
  const bool linearised = state.range(2) != 0;
  Eigen::Isometry3d robot_from_sensor = Eigen::Isometry3d::Identity();
  if (linearised) {
    robot_from_sensor.translation() = Eigen::Vector3d(0.0, 0.0, -10.0);  // optical z is the robot's z
  }
  constexpr std::uint32_t kUpdates = 10;
  std::vector<Scenario> batches;
  std::vector<core::Pose2> poses;  // the robot drives 0.1 m and turns 0.02 rad per update
  for (std::uint32_t u = 0; u < kUpdates; ++u) {
    poses.push_back(core::Pose2{0.1 * (u + 1), 0.0, 0.02 * (u + 1)});
    batches.push_back(make_scenario(landmarks, u + 1));
    const Eigen::Isometry3d sensor_from_map = (poses.back().to_isometry3() * robot_from_sensor).inverse();
    for (core::LandmarkObservation& o : batches.back().observations) {
      o.point_camera = sensor_from_map * o.point_camera;
    }
  }
  core::FilterConfig config;
  config.particles = static_cast<int>(particles);
  config.particle_capacity = config.particles;
  config.linearise_at_estimate = linearised;
  const StereoModel stereo{400.0, 319.5, 239.5, 0.1, 10.0, 10.0, 0.5};
  config.landmark_node_capacity =
      static_cast<int>(2 * landmarks + kUpdates * particles * path_nodes_per_update(landmarks) + 1000);
  config.landmark_estimate_capacity = static_cast<int>(landmarks + kUpdates * particles * kObservationsPerUpdate + 1000);
  config.trajectory_node_capacity = static_cast<int>((kUpdates + 2) * particles + 10);
  // The dropped maps' release on the timed thread, as before filter.background_release: here
  // the updates run back to back, so the release would overlap nothing and its CPU time would
  // only move to the worker thread, out of the figure. The stack's gain from it is measured on
  // whole runs (docs/results.md, "Speed of the simulated run").
  config.background_release = false;
  ParticleFilter filter(config, core::CameraMount{}, 1, &stereo);
  std::size_t nodes_held = 0;
  for (auto _ : state) {
    state.PauseTiming();
    filter.start(core::OdometryReading{}, {}, batches[0].prior.data(), batches[0].prior.size());
    state.ResumeTiming();
    for (std::uint32_t u = 0; u < kUpdates; ++u) {
      const Scenario& batch = batches[u];
      const core::OdometryReading odometry{u + 1, u + 1, poses[u]};
      filter.update(odometry, ObservationList{batch.observations.data(), batch.observations.size()},
                    robot_from_sensor);
    }
    state.PauseTiming();
    nodes_held = filter.landmarks().nodes_in_use();
    state.ResumeTiming();
  }
  state.counters["updates"] = kUpdates;  // the time shown is for all of them
  state.counters["nodes_held"] = static_cast<double>(nodes_held);
  state.counters["resamplings"] = static_cast<double>(filter.counters().resamplings);
  state.counters["refused"] = static_cast<double>(filter.counters().changes_refused_pool_full);
}
BENCHMARK(BM_ConsecutiveUpdates)
    ->Args({1000, 10000, 0})
    ->Args({2000, 10000, 0})
    ->Args({1000, 10000, 1})
    ->ArgNames({"particles", "landmarks", "linearised"})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);

// The baseline: every particle owns a flat array of K estimates; resampling copies N of them.
void BM_CopyWholeMapResample(benchmark::State& state) {
  const auto particles = static_cast<std::size_t>(state.range(0));
  const auto landmarks = static_cast<std::size_t>(state.range(1));
  std::vector<std::vector<LandmarkEstimate>> maps(particles, std::vector<LandmarkEstimate>(landmarks));
  std::vector<std::vector<LandmarkEstimate>> next(particles, std::vector<LandmarkEstimate>(landmarks));
  core::RandomStream pick(9, {core::stream_purpose::test, 0, 2});
  for (auto _ : state) {
    for (std::size_t i = 0; i < particles; ++i) {
      const std::vector<LandmarkEstimate>& source = maps[pick.uniform_index(static_cast<std::uint32_t>(particles))];
      std::copy(source.begin(), source.end(), next[i].begin());
    }
    std::swap(maps, next);
    benchmark::ClobberMemory();
  }
  state.counters["copy_map_MB"] = static_cast<double>(particles * landmarks * sizeof(LandmarkEstimate)) / 1e6;
}
BENCHMARK(BM_CopyWholeMapResample)
    ->Args({100, 1000})
    ->Args({100, 10000})
    ->Args({1000, 1000})
    ->Args({1000, 10000})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace
}  // namespace stereoscout::slam

BENCHMARK_MAIN();
