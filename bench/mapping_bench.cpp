#include <benchmark/benchmark.h>

#include "bench/mapping_scene.hpp"
#include "bipednav/mapping/heightmap_fusion.hpp"
#include "bipednav/mapping/inflation.hpp"
#include "bipednav/mapping/local_costmap.hpp"

namespace {

using namespace bipednav::mapping;
using namespace bipednav::bench;

// Inflation of the 160 x 160 local map holding one synthetic Digit frame's obstacles.
void BM_Inflation160(benchmark::State& state) {
  LocalCostmap local;
  local.update({0.0, 0.0, 0.0}, synthetic_digit_observations({0.0, 0.0, 0.0}).observations);
  Inflator inflator(local.params().inflation(), local.params().resolution_m);
  Costmap2D out;
  for (auto _ : state) {
    inflator.inflate(local.obstacles(), out);
    benchmark::DoNotOptimize(out.data().data());
  }
}
BENCHMARK(BM_Inflation160);

// Local costmap update (re-centre, marking, ray-trace clearing, inflation) from one full frame.
void BM_LocalCostmapUpdate(benchmark::State& state) {
  const auto frame = synthetic_digit_observations({0.0, 0.0, 0.0});
  LocalCostmap local;
  for (auto _ : state) benchmark::DoNotOptimize(local.update({0.0, 0.0, 0.0}, frame.observations));
}
BENCHMARK(BM_LocalCostmapUpdate)->Unit(benchmark::kMillisecond);

// Heightmap fusion of 300k points into a 2.5 x 2.5 m map at 1 cm.
void BM_Heightmap300k(benchmark::State& state) {
  bipednav::Rng rng(1);
  const auto cloud = synthetic_terrain_cloud(300000, 2.5, rng);
  HeightmapFusion fusion({250, 250, 0.01, 0.0, 0.0});
  for (auto _ : state) benchmark::DoNotOptimize(fusion.update(cloud, Eigen::Vector3d(1.25, -0.5, 1.5)));
}
BENCHMARK(BM_Heightmap300k)->Unit(benchmark::kMillisecond);

}  // namespace
