// Micro-benchmarks of the perception kernels on a synthetic Digit frame.
#include <benchmark/benchmark.h>

#include "bipednav/perception/ground_segmentation.hpp"
#include "bipednav/perception/pipeline.hpp"
#include "bipednav/perception/synthetic_scene.hpp"
#include "bipednav/perception/voxel_grid.hpp"

namespace {

using namespace bipednav;

const SensorFrame& digit_frame() {
  static const SensorFrame frame = perception::synthetic_digit_frame(perception::synthetic_digit_profile());
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

void BM_RansacLidarSweep(benchmark::State& state) {
  perception::RansacParams p;
  Rng rng(1);
  for (auto _ : state) benchmark::DoNotOptimize(perception::fit_plane_ransac(digit_frame().lidar->points, p, rng));
}
BENCHMARK(BM_RansacLidarSweep)->Unit(benchmark::kMicrosecond);

void BM_PipelineDigitFrame(benchmark::State& state) {
  const RobotProfile robot = perception::synthetic_digit_profile();
  perception::PerceptionPipeline pipe{perception::PerceptionParams{}};
  for (auto _ : state) benchmark::DoNotOptimize(pipe.process(digit_frame(), robot));
}
BENCHMARK(BM_PipelineDigitFrame)->Unit(benchmark::kMicrosecond);

}  // namespace
