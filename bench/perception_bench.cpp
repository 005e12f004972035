// Micro-benchmarks of the perception kernels on a synthetic Digit frame.
#include <benchmark/benchmark.h>

#include "bench/synthetic_scene.hpp"
#include "bipednav/perception/ground_segmentation.hpp"
#include "bipednav/perception/pass_through.hpp"
#include "bipednav/perception/pipeline.hpp"
#include "bipednav/perception/voxel_grid.hpp"

namespace {

using namespace bipednav;

const SensorFrame& digit_frame() {
  static const SensorFrame frame = bench::synthetic_digit_frame(bench::synthetic_digit_profile());
  return frame;
}

void BM_VoxelGridDepthCloud(benchmark::State& state) {
  perception::VoxelGrid grid;
  PointCloud out;
  for (auto _ : state) {
    grid.filter(digit_frame().depth.front().cloud, out);
    benchmark::DoNotOptimize(out.points.data());
  }
}
BENCHMARK(BM_VoxelGridDepthCloud)->Unit(benchmark::kMicrosecond);

// As the pipeline runs it: the 2.9 m range crop tested on the fly (section 4.2.2).
void BM_VoxelGridDepthCloudCropped(benchmark::State& state) {
  perception::VoxelGrid grid;
  perception::PassThroughParams range;
  range.max_range_m = 2.9;
  const perception::PassThroughTest crop(range);
  PointCloud out;
  for (auto _ : state) {
    grid.filter(digit_frame().depth.front().cloud, out, &crop);
    benchmark::DoNotOptimize(out.points.data());
  }
}
BENCHMARK(BM_VoxelGridDepthCloudCropped)->Unit(benchmark::kMicrosecond);

void BM_RansacLidarSweep(benchmark::State& state) {
  perception::RansacParams p;
  Rng rng(1);
  perception::RansacScratch scratch;
  for (auto _ : state)
    benchmark::DoNotOptimize(perception::fit_plane_ransac(digit_frame().lidar->points, p, rng, &scratch));
}
BENCHMARK(BM_RansacLidarSweep)->Unit(benchmark::kMicrosecond);

void BM_PipelineDigitFrame(benchmark::State& state) {
  const RobotProfile robot = bench::synthetic_digit_profile();
  perception::PerceptionPipeline pipe{perception::PerceptionParams{}};
  for (auto _ : state) benchmark::DoNotOptimize(pipe.process(digit_frame(), robot));
}
BENCHMARK(BM_PipelineDigitFrame)->Unit(benchmark::kMicrosecond);

}  // namespace
