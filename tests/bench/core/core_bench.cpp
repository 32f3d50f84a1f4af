// Speed of the core building blocks that every update leans on.
#include <benchmark/benchmark.h>

#include <vector>

#include "stereoscout/core/fixed_pool.hpp"
#include "stereoscout/core/random.hpp"
#include "stereoscout/core/shared_pool.hpp"

namespace stereoscout::core {
namespace {

void BM_PhiloxBlock(benchmark::State& state) {
  PhiloxCounter counter{0, 1, 2, 3};
  for (auto _ : state) {
    counter = philox4x32_10(counter, {7, 9});
    benchmark::DoNotOptimize(counter);
  }
}
BENCHMARK(BM_PhiloxBlock);

void BM_Gaussian(benchmark::State& state) {
  RandomStream stream(1, {stream_purpose::test, 0, 0});
  for (auto _ : state) {
    benchmark::DoNotOptimize(stream.gaussian());
  }
}
BENCHMARK(BM_Gaussian);

void BM_PoolAcquireRelease(benchmark::State& state) {
  const auto live = static_cast<std::size_t>(state.range(0));
  FixedPool<double> pool(live + 1);
  std::vector<Handle<double>> held;
  for (std::size_t i = 0; i < live; ++i) {
    held.push_back(pool.acquire(1.0));
  }
  for (auto _ : state) {
    const Handle<double> handle = pool.acquire(2.0);
    benchmark::DoNotOptimize(pool.get(handle));
    pool.release(handle);
  }
}
BENCHMARK(BM_PoolAcquireRelease)->Arg(0)->Arg(1 << 20);

void BM_SharedRetainRelease(benchmark::State& state) {
  SharedPool<double> pool(16);
  const Handle<double> handle = pool.acquire(1.0);
  for (auto _ : state) {
    pool.retain(handle);
    benchmark::DoNotOptimize(pool.release(handle));
  }
}
BENCHMARK(BM_SharedRetainRelease);

}  // namespace
}  // namespace stereoscout::core

BENCHMARK_MAIN();
