// Speed of the vision front end (issue 4): SIFT on a 640x480 pair, stereo matching, the
// descriptor index lookup versus its size, dense disparity (640x480, 64 disparities) and the
// 2.5D scan. Images come from the synthetic renderer of the unit tests (a textured room).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <memory>
#include <vector>

#include "stereoscout/core/random.hpp"
#include "stereoscout/vision/front_end.hpp"
#include "synthetic_stereo.hpp"

namespace stereoscout::vision {
namespace {

core::CameraMount paper_mount() { return {0.10, 0.0, 0.6, 0.0}; }

const test::Rendering& room_view() {
  static const test::Rendering view =
      test::render(test::textured_room(), StereoCalibration{}, paper_mount(), core::Pose2{0.0, 0.0, 0.1});
  return view;
}

void BM_SiftOneImage(benchmark::State& state) {
  SiftExtractor sift(sift_params_from_config(core::VisionConfig{}));
  core::FixedVector<Keypoint> keys(1000);
  for (auto _ : state) {
    sift.extract(room_view().frame.right, keys);
    benchmark::DoNotOptimize(keys.size());
  }
  state.counters["keys"] = static_cast<double>(keys.size());
}
BENCHMARK(BM_SiftOneImage)->Unit(benchmark::kMillisecond);

// The whole landmark path of one pair: SIFT x2, matching, triangulation, index.
void BM_FrontEndLandmarks(benchmark::State& state) {
  core::VisionConfig config;
  config.sift_parallel = state.range(0) != 0;
  VisionFrontEnd front_end(config, core::RobotConfig{}, StereoCalibration{}, paper_mount());
  core::FixedVector<core::LandmarkObservation> observations(front_end.max_observations());
  for (auto _ : state) {
    front_end.observe_landmarks(room_view().frame, observations);
  }
  state.counters["matches"] = static_cast<double>(front_end.last_frame_stats().stereo_matches);
}
BENCHMARK(BM_FrontEndLandmarks)->Arg(0)->Arg(1)->ArgName("parallel")->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_StereoMatching(benchmark::State& state) {
  SiftExtractor sift(sift_params_from_config(core::VisionConfig{}));
  core::FixedVector<Keypoint> left(1000);
  core::FixedVector<Keypoint> right(1000);
  sift.extract(room_view().frame.left, left);
  sift.extract(room_view().frame.right, right);
  StereoMatchParams params;
  params.cross_check = state.range(0) != 0;
  StereoMatcher matcher(params, 480, 1000);
  core::FixedVector<StereoMatch> matches(1000);
  for (auto _ : state) {
    matcher.match(left, right, matches);
    benchmark::DoNotOptimize(matches.size());
  }
  state.counters["matches"] = static_cast<double>(matches.size());
}
BENCHMARK(BM_StereoMatching)->Arg(0)->Arg(1)->ArgName("cross_check")->Unit(benchmark::kMicrosecond);

// One lookup (64 or 1024 leaf checks: vision.index_max_leaf_checks) in an index holding N
// random descriptors. The index is built once per size (Google Benchmark calls the function
// several times), with its search heap sized for the deepest search benchmarked.
// Queries (kind): 0, stored descriptors with noise of +-1 per byte, about 10 from their source
// (the same key seen again from the same place); 1, noise of +-20, about 135 from it, under the
// match distance (a key seen from elsewhere), where a bounded search can stop short of the
// source; 2, fresh random descriptors, about 295 from every entry (a key seen for the first
// time, as most are). found_source counts the lookups that found the query's source.
// box 1: the search orders cells by their exact distance (vision.index_box_distance) and
// stops at the match distance, as DescriptorIndex::observe searches.
constexpr int kDeepestLeafChecks = 1024;
constexpr std::size_t kQueries = 1024;
constexpr std::uint32_t kMatchDistanceSquared = 180 * 180;  // vision.index_match_distance

struct IndexFixture {
  std::unique_ptr<DescriptorIndex> index;  // searched by the largest gap
  std::unique_ptr<DescriptorIndex> box_index;  // the same entries, searched by box distance
  std::vector<Descriptor> sources;          // the first kQueries stored descriptors
  std::vector<std::uint32_t> source_entries;
};

IndexFixture& index_of_size(std::size_t size) {
  static std::map<std::size_t, IndexFixture> fixtures;
  IndexFixture& fixture = fixtures[size];
  if (!fixture.index) {
    DescriptorIndexParams params;
    params.capacity = size;
    params.candidate_min_frames = 1;
    params.max_leaf_checks = kDeepestLeafChecks;
    fixture.index = std::make_unique<DescriptorIndex>(params);
    fixture.index->set_max_leaf_checks(1);  // building: random keys are all new anyway
    params.box_distance = true;
    fixture.box_index = std::make_unique<DescriptorIndex>(params);
    fixture.box_index->set_max_leaf_checks(1);
    core::RandomStream random(1, core::StreamId{0, 0, 0});
    for (std::size_t i = 0; i < size; ++i) {
      Descriptor descriptor{};
      for (auto& value : descriptor) value = static_cast<std::uint8_t>(random.uniform_index(64));
      const IndexLookup stored = fixture.index->observe(descriptor, 0);
      fixture.box_index->observe(descriptor, 0);
      if (fixture.sources.size() < kQueries) {
        fixture.sources.push_back(descriptor);
        fixture.source_entries.push_back(stored.entry);
      }
    }
  }
  return fixture;
}

std::vector<Descriptor> index_queries(const std::vector<Descriptor>& sources, int kind) {
  core::RandomStream random(2, core::StreamId{0, 0, 0});
  std::vector<Descriptor> queries = sources;
  const int noise = kind == 0 ? 1 : 20;
  const auto span = static_cast<std::uint32_t>(2 * noise + 1);
  for (Descriptor& query : queries) {
    for (auto& value : query) {
      const int noisy = static_cast<int>(value) + static_cast<int>(random.uniform_index(span)) - noise;
      value = kind == 2 ? static_cast<std::uint8_t>(random.uniform_index(64))
                        : static_cast<std::uint8_t>(std::clamp(noisy, 0, 255));
    }
  }
  return queries;
}

void BM_IndexLookup(benchmark::State& state) {
  IndexFixture& fixture = index_of_size(static_cast<std::size_t>(state.range(0)));
  DescriptorIndex& index = state.range(3) != 0 ? *fixture.box_index : *fixture.index;
  index.set_max_leaf_checks(static_cast<int>(state.range(1)));
  const std::vector<Descriptor> queries = index_queries(fixture.sources, static_cast<int>(state.range(2)));
  const std::uint64_t leaves_before = index.stats().leaves_checked;
  const std::uint64_t lookups_before = index.stats().lookups;
  std::size_t next = 0;
  std::uint64_t found_source = 0;
  for (auto _ : state) {
    const IndexNeighbour neighbour = index.nearest(queries[next], kMatchDistanceSquared);
    found_source += neighbour.found && neighbour.entry == fixture.source_entries[next] ? 1U : 0U;
    next = (next + 1) % queries.size();
  }
  const auto lookups = static_cast<double>(index.stats().lookups - lookups_before);
  state.counters["leaves_per_lookup"] = static_cast<double>(index.stats().leaves_checked - leaves_before) / lookups;
  // Share of lookups that found the entry their query was made from (the true neighbour).
  state.counters["found_source"] = static_cast<double>(found_source) / lookups;
}
BENCHMARK(BM_IndexLookup)
    ->ArgsProduct({{1000, 10000, 100000, 1000000}, {64, kDeepestLeafChecks}, {0, 1, 2}, {0, 1}})
    ->ArgNames({"entries", "leaf_checks", "query", "box"})
    ->Unit(benchmark::kMicrosecond);

// simd 1: the build of the inner loops the CPU runs best (label: which); 0: the portable one.
// area_rule 0: the speckle filter without its area rule (vision.dense_speckle_min_area_m2 = 0).
// disparities: vision.dense_num_disparities (a wider search measures nearer surfaces: 0.42 m
// from the camera at 96 against 0.63 m at 64, docs/results.md).
void BM_DenseDisparity(benchmark::State& state) {
  core::VisionConfig vision;
  if (state.range(1) == 0) vision.dense_speckle_min_area_m2 = 0.0;
  vision.dense_num_disparities = static_cast<int>(state.range(2));
  DenseDisparityParams params = dense_params_from_config(vision, core::CameraConfig{}.baseline_m);
  params.allow_simd = state.range(0) != 0;
  DenseDisparityMatcher matcher(params, 640, 480);
  cv::Mat disparity;
  matcher.allocate_output(disparity);
  for (auto _ : state) {
    matcher.compute(room_view().frame.left, room_view().frame.right, disparity);
  }
  state.counters["density"] = static_cast<double>(matcher.stats().valid) / static_cast<double>(matcher.stats().pixels);
  state.SetLabel(matcher.kernels_name());
}
BENCHMARK(BM_DenseDisparity)
    ->Args({1, 1, 64})
    ->Args({1, 0, 64})
    ->Args({0, 1, 64})
    ->Args({1, 1, 96})
    ->Args({1, 1, 128})
    ->ArgNames({"simd", "area_rule", "disparities"})
    ->Unit(benchmark::kMillisecond);

void BM_ObstacleScan(benchmark::State& state) {
  DenseDisparityMatcher matcher(dense_params_from_config(core::VisionConfig{}, core::CameraConfig{}.baseline_m), 640, 480);
  cv::Mat disparity;
  matcher.allocate_output(disparity);
  matcher.compute(room_view().frame.left, room_view().frame.right, disparity);
  ObstacleScanner scanner(scan_params_from_config(core::VisionConfig{}, core::RobotConfig{}), StereoCalibration{},
                          paper_mount());
  core::DepthScan scan;
  scanner.allocate(scan);
  // With the left image the scan also looks for blank walls' bases (wall_base.hpp).
  const cv::Mat left = state.range(0) != 0 ? room_view().frame.left : cv::Mat();
  for (auto _ : state) {
    scanner.compute(disparity, left, 0.0, 0, scan);
  }
}
BENCHMARK(BM_ObstacleScan)->Arg(0)->Arg(1)->ArgName("left_image")->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace stereoscout::vision

BENCHMARK_MAIN();
