// Speed of the simulator: rendering a 640x480 stereo pair (target: under 10 ms on one core),
// the kinematics step, and the ground-truth rasterisation.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>

#include "stereoscout/host_sim/ground_truth.hpp"
#include "stereoscout/host_sim/renderer.hpp"
#include "stereoscout/host_sim/simulator.hpp"

namespace stereoscout::host_sim {
namespace {

const World& world(const char* name) {
  static World worlds[3];
  static const char* names[3] = {"lab", "office", "clutter"};
  for (int i = 0; i < 3; ++i) {
    if (std::string(name) != names[i]) continue;
    if (worlds[i].walls.empty()) {
      const std::string path = std::string(STEREOSCOUT_BENCH_SOURCE_DIR) + "/config/worlds/" + name + ".yaml";
      WorldLoad load = load_world(path);
      if (!load.ok()) {
        std::fprintf(stderr, "%s", load.error_text().c_str());
        std::abort();
      }
      worlds[i] = std::move(load.world);
    }
    return worlds[i];
  }
  std::abort();
}

// Renders the pair (and the ground-truth depth) from poses along a loop through the world.
// texture_variants: 0 keeps the world's own.
void render_pair(benchmark::State& state, const char* name, bool with_depth, int texture_variants = 0) {
  const core::CameraConfig camera;
  World w = world(name);
  if (texture_variants > 0) w.texture_variants = texture_variants;
  StereoRenderer renderer(w, camera, core::SimConfig{}, 1);
  cv::Mat left(camera.height_px, camera.width_px, CV_8UC1);
  cv::Mat right(camera.height_px, camera.width_px, CV_8UC1);
  cv::Mat depth(camera.height_px, camera.width_px, CV_32FC1);
  const Eigen::Vector2d low = w.bounds_min();
  const Eigen::Vector2d high = w.bounds_max();
  std::uint32_t frame = 0;
  for (auto _ : state) {
    // Deterministic walk over 16 headings and positions inside the bounds.
    const double t = static_cast<double>(frame % 64) / 64.0;
    const core::Pose2 pose{low.x() + (0.2 + 0.6 * t) * (high.x() - low.x()), low.y() + (0.3 + 0.4 * t) * (high.y() - low.y()),
                           core::wrap_angle(0.4 * frame)};
    renderer.render(pose, 0.0, 0.1 * frame, frame, left, right, with_depth ? &depth : nullptr);
    benchmark::DoNotOptimize(left.data);
    ++frame;
  }
  state.SetLabel(name);
}

void BM_RenderStereoPairLab(benchmark::State& state) { render_pair(state, "lab", false); }
void BM_RenderStereoPairWithDepthLab(benchmark::State& state) { render_pair(state, "lab", true); }
void BM_RenderStereoPairOffice(benchmark::State& state) { render_pair(state, "office", false); }
void BM_RenderStereoPairClutter(benchmark::State& state) { render_pair(state, "clutter", false); }
// Each texel read hashes its 2.56 m cell to pick the cell's tile.
void BM_RenderStereoPairOfficeTextureVariants8(benchmark::State& state) { render_pair(state, "office", false, 8); }
// Start-up: the office's tiles, one per texture or eight per texture it shows.
void BM_TextureBankOffice(benchmark::State& state) {
  World w = world("office");
  w.texture_variants = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const TextureBank bank(w);
    benchmark::DoNotOptimize(bank.level(Texture::carpet, 0).texels);
  }
}
BENCHMARK(BM_RenderStereoPairLab)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderStereoPairWithDepthLab)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderStereoPairOffice)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderStereoPairClutter)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RenderStereoPairOfficeTextureVariants8)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TextureBankOffice)->Arg(1)->Arg(8)->Unit(benchmark::kMillisecond);

// One second of simulated driving (100 kinematics steps with collision checks, 5-6 odometry
// readings); with the argument 1 the near misses are counted too (a clearance query a step).
void BM_SimulateOneSecondLab(benchmark::State& state) {
  const World& w = world("lab");
  core::SimConfig sim;
  sim.near_miss_m = state.range(0) != 0 ? sim.near_miss_m : 0.0;
  Simulator simulator(w, core::RobotConfig{}, core::CameraConfig{}, sim, 1);
  OdometrySample sample;
  for (auto _ : state) {
    simulator.command({0.1, 0.05});
    simulator.step(1.0);
    while (simulator.pop_odometry(sample)) {
    }
    if (simulator.current_command().linear_mps == 0.0) simulator.teleport(w.start);
  }
}
BENCHMARK(BM_SimulateOneSecondLab)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_RasterizeLab(benchmark::State& state) {
  const World& w = world("lab");
  for (auto _ : state) {
    const GroundTruthGrid grid = rasterize_world(w, 0.05, 0.02, 1.2);
    benchmark::DoNotOptimize(grid.cells.data());
  }
}
BENCHMARK(BM_RasterizeLab)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stereoscout::host_sim

BENCHMARK_MAIN();
