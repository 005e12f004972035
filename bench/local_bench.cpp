#include <benchmark/benchmark.h>

#include "bench/local_scene.hpp"
#include "bipednav/planning/local/costmap_obstacles.hpp"
#include "bipednav/planning/local/teb_planner.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::planning::local;
using namespace bipednav::bench;

// One TEB cycle (warm-started) at the start of the bench scene, homotopy classes on.
void BM_TebCycle(benchmark::State& state) {
  const auto scene = make_local_bench_scene(static_cast<int>(state.range(0)), 42);
  TebPlanner planner(TebParams{});
  planner.compute(scene.start, {}, scene.plan, scene.costmap, 0.0);
  for (auto _ : state) {
    auto r = planner.compute(scene.start, {}, scene.plan, scene.costmap, 0.0);
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_TebCycle)->Arg(0)->Arg(20)->Arg(100)->Unit(benchmark::kMillisecond);

void BM_ExtractObstacles(benchmark::State& state) {
  const auto scene = make_local_bench_scene(static_cast<int>(state.range(0)), 42);
  ObstacleScratch scratch;
  for (auto _ : state) {
    auto obs = extract_obstacles(scene.costmap, ObstacleParams{}, &scratch);
    benchmark::DoNotOptimize(obs);
  }
}
BENCHMARK(BM_ExtractObstacles)->Arg(20)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace
