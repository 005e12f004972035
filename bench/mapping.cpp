#include "bench/mapping.hpp"

#include <algorithm>
#include <vector>

#include "bench/mapping_scene.hpp"
#include "bipednav/common/clock.hpp"
#include "bipednav/common/cpu_time.hpp"
#include "bipednav/mapping/global_costmap.hpp"
#include "bipednav/mapping/heightmap_fusion.hpp"
#include "bipednav/mapping/local_costmap.hpp"

namespace bipednav::bench {
namespace {

using namespace bipednav::mapping;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
double maximum(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }

}  // namespace

nlohmann::json run_mapping_bench(const MappingBenchOptions& options) {
  const int iterations = options.iterations;
  // Local costmap: the robot walks 5 cm per update through the room, one full frame each time.
  std::vector<SyntheticObservations> frames;
  for (int i = 0; i < std::min(iterations, 40); ++i)
    frames.push_back(synthetic_digit_observations({-1.0 + 0.05 * i, 0.2, 0.1 * i}));
  LocalCostmap local;
  local.update({-1.05, 0.2, 0.0}, frames[0].observations);
  std::vector<double> local_ms, infl_ms, global_ms, height_ms, local_cpu, height_cpu;
  GlobalCostmap global(GlobalCostmap::default_geometry({0.0, 0.0, 0.0}));
  for (int i = 0; i < iterations; ++i) {
    const auto& f = frames[i % frames.size()];
    const Pose2 pose{-1.0 + 0.05 * (i % frames.size()), 0.2, 0.1 * (i % frames.size())};
    const double c0 = thread_cpu_ms();
    Stopwatch sw;
    local.update(pose, f.observations);
    local_ms.push_back(sw.elapsed_ms());
    local_cpu.push_back(thread_cpu_ms() - c0);
    sw.restart();
    global.update(pose, {f.observations[0]}, &local);
    global_ms.push_back(sw.elapsed_ms());
  }
  Inflator inflator(local.params().inflation(), local.params().resolution_m);
  Costmap2D inflated;
  for (int i = 0; i < std::max(iterations, 200); ++i) {
    Stopwatch sw;
    inflator.inflate(local.obstacles(), inflated);
    infl_ms.push_back(sw.elapsed_ms());
  }
  Rng rng(1);
  const auto cloud = synthetic_terrain_cloud(300000, 2.5, rng);
  HeightmapFusion fusion({250, 250, 0.01, 0.0, 0.0});
  for (int i = 0; i < std::max(5, iterations / 4); ++i) {
    const double c0 = thread_cpu_ms();
    Stopwatch sw;
    fusion.update(cloud, Eigen::Vector3d(1.25, -0.5, 1.5));
    height_ms.push_back(sw.elapsed_ms());
    height_cpu.push_back(thread_cpu_ms() - c0);
  }
  const double lm = median(local_ms), im = median(infl_ms), hm = median(height_ms);
  return {{"iterations", iterations},
          {"frame_lidar_points", frames[0].lidar_points},
          {"frame_depth_points", frames[0].depth_points},
          {"local_grid_cells", local.geometry().size()},
          {"local_update_median_ms", lm},
          {"local_update_max_ms", maximum(local_ms)},
          {"local_update_cpu_median_ms", median(local_cpu)},
          {"meets_goal_local_update_cpu_median", median(local_cpu) < 5.0},
          {"goal_local_update_median_ms", 5.0},
          {"meets_goal_local_update_median", lm < 5.0},
          {"inflation_160x160_median_ms", im},
          {"goal_inflation_160x160_median_ms", 0.1},
          {"meets_goal_inflation_160x160_median", im < 0.1},
          {"heightmap_points", cloud.size()},
          {"heightmap_cells", fusion.map().geometry().size()},
          {"heightmap_update_median_ms", hm},
          {"heightmap_update_cpu_median_ms", median(height_cpu)},
          {"meets_goal_heightmap_update_cpu_median", median(height_cpu) < 5.0},
          {"goal_heightmap_update_median_ms", 5.0},
          {"meets_goal_heightmap_update_median", hm < 5.0},
          {"paper_heightmap_update_ms", 70.0},
          {"global_update_400x400_median_ms", median(global_ms)},
          {"global_update_400x400_max_ms", maximum(global_ms)}};
}

}  // namespace bipednav::bench
