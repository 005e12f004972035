#include "bench/perception.hpp"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "bench/synthetic_scene.hpp"
#include "bipednav/common/clock.hpp"
#include "bipednav/common/cpu_time.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/io/robot_profile_yaml.hpp"
#include "bipednav/perception/ground_segmentation.hpp"
#include "bipednav/perception/pass_through.hpp"
#include "bipednav/perception/pipeline.hpp"
#include "bipednav/perception/voxel_grid.hpp"
#include "bipednav/sim/scenario.hpp"
#include "bipednav/sim/simulation.hpp"

namespace bipednav::bench {
namespace {

using perception::PassThroughParams;

// Looks for <rel> or tests/data/<rel> in the working directory, the executable's, and the folders above them.
std::filesystem::path find_file(const std::string& rel) {
  std::error_code ec;
  for (std::filesystem::path dir :
       {std::filesystem::current_path(), std::filesystem::read_symlink("/proc/self/exe", ec).parent_path()}) {
    for (int up = 0; up < 6 && !dir.empty(); ++up, dir = dir.parent_path()) {
      for (const std::filesystem::path& c : {dir / rel, dir / "tests" / "data" / rel})
        if (std::filesystem::exists(c)) return c;
      if (dir == dir.parent_path()) break;
    }
  }
  return {};
}

struct Timing {
  double cpu_ms = 0.0, wall_ms = 0.0;  // medians
};

Timing median_timing(int reps, const std::function<void(int)>& f) {
  std::vector<double> cpu, wall;
  for (int r = 0; r < reps; ++r) {
    const Stopwatch sw;
    const double c0 = thread_cpu_ms();
    f(r);
    cpu.push_back(thread_cpu_ms() - c0);
    wall.push_back(sw.elapsed_ms());
  }
  std::sort(cpu.begin(), cpu.end());
  std::sort(wall.begin(), wall.end());
  return {cpu[cpu.size() / 2], wall[wall.size() / 2]};
}

double reduction_percent(std::size_t in, std::size_t out) {
  return in ? 100.0 * (1.0 - double(out) / double(in)) : 0.0;
}

std::size_t finite_count(const PointCloud& c) {
  std::size_t n = 0;
  for (const auto& p : c.points) n += p.allFinite() ? 1u : 0u;
  return n;
}

nlohmann::json voxel_figures(const PointCloud& c, double leaf_m, int reps) {
  perception::VoxelGridParams v;
  v.leaf_size_m.setConstant(leaf_m);
  perception::VoxelGrid grid(v);
  PointCloud out;
  const Timing t = median_timing(reps, [&](int) { grid.filter(c, out); });
  return {{"points", c.size()},
          {"finite_points", finite_count(c)},
          {"leaf_m", leaf_m},
          {"voxels", out.size()},
          {"median_ms", t.cpu_ms},
          {"median_wall_ms", t.wall_ms},
          {"reduction_percent", reduction_percent(finite_count(c), out.size())}};
}

nlohmann::json ransac_figures(const PointCloud& c, double threshold_m, int reps) {
  perception::RansacParams p;
  p.distance_threshold_m = threshold_m;
  perception::PlaneFit fit;
  std::vector<std::size_t> inliers;
  perception::RansacScratch scratch;  // reused as the pipeline reuses its own
  const Timing t = median_timing(reps, [&](int r) {
    Rng rng(static_cast<std::uint64_t>(r) + 1);
    fit = perception::fit_plane_ransac(c.points, p, rng, &scratch);
    inliers.push_back(fit.inliers);
  });
  std::sort(inliers.begin(), inliers.end());
  return {{"points", c.size()},
          {"distance_threshold_m", threshold_m},
          {"median_ms", t.cpu_ms},
          {"median_wall_ms", t.wall_ms},
          {"median_inliers", inliers[inliers.size() / 2]},
          {"min_inliers", inliers.front()},
          {"plane", {fit.plane[0], fit.plane[1], fit.plane[2], fit.plane[3]}},
          {"iterations", fit.iterations}};
}

nlohmann::json pcl_figures(int reps) {
  nlohmann::json j;
  const std::filesystem::path table = find_file("pcl/table_scene_mug_stereo_textured.pcd");
  const std::filesystem::path plane = find_file("pcl/sac_plane_test.pcd");
  if (table.empty() || plane.empty()) return {{"skipped", "PCL test clouds not found (tests/data/pcl)"}};
  const PointCloud raw = io::read_pcd(table);
  PassThroughParams band;
  band.min_height_m = 0.0;
  band.max_height_m = 1.5;
  j["table_scene_voxel_0.01"] = voxel_figures(raw, 0.01, reps);
  j["table_scene_ransac_0.03"] = ransac_figures(perception::pass_through(raw, band), 0.03, reps);
  j["sac_plane_test_ransac_0.03"] = ransac_figures(io::read_pcd(plane), 0.03, reps);
  return j;
}

nlohmann::json frame_figures(const SensorFrame& frame, const RobotProfile& robot, int reps) {
  perception::PerceptionPipeline pipe{perception::PerceptionParams{}};
  perception::PerceptionOutput out;
  std::vector<double> depth, lidar, seg;
  const Timing t = median_timing(reps, [&](int) {
    out = pipe.process(frame, robot);
    depth.push_back(out.timings.depth_ms);
    lidar.push_back(out.timings.lidar_ms);
    seg.push_back(out.timings.segmentation_ms);
  });
  const auto med = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  return {{"depth_clouds", frame.depth.size()},
          {"lidar_points", frame.lidar ? frame.lidar->size() : 0},
          {"depth_points_finite", out.depth_points_in},
          {"depth_points_after_range_and_voxel", out.depth_points_voxel},
          {"median_ms", t.cpu_ms},
          {"median_wall_ms", t.wall_ms},
          {"depth_stage_median_wall_ms", med(depth)},
          {"lidar_stage_median_wall_ms", med(lidar)},
          {"segmentation_stage_median_wall_ms", med(seg)},
          {"plane_from_ransac", out.plane_from_ransac},
          {"ground_plane", {out.ground_plane[0], out.ground_plane[1], out.ground_plane[2], out.ground_plane[3]}},
          {"ground_points", out.ground.size()},
          {"obstacle_points", out.obstacles.size()},
          {"goal_median_ms", 5.0},
          {"meets_goal_median", t.cpu_ms < 5.0}};
}

// Digit frames from the simulator (scenarios/digit_lab_static.yaml, config/digit.yaml): the last
// complete frame (two depth clouds + one sweep) and every depth cloud seen, for the reduction.
struct DigitFrames {
  std::string source;
  RobotProfile robot;
  SensorFrame frame;
  std::vector<PointCloud> depth_clouds;
};

DigitFrames simulated_digit_frames() {
  DigitFrames d;
  const std::filesystem::path scenario = find_file("scenarios/digit_lab_static.yaml");
  const std::filesystem::path profile = find_file("config/digit.yaml");
  if (scenario.empty() || profile.empty()) {
    d.source = "synthetic (scenarios/digit_lab_static.yaml or config/digit.yaml not found)";
    d.robot = bench::synthetic_digit_profile();
    d.frame = bench::synthetic_digit_frame(d.robot);
    for (const auto& c : d.frame.depth) d.depth_clouds.push_back(c.cloud);
    return d;
  }
  const sim::Scenario sc = sim::load_scenario(scenario);
  d.robot = io::load_robot_profile(profile);
  d.source = "simulated: " + sc.name + " with " + d.robot.name + ", 2 s of walking";
  sim::SimulationParams params;
  params.seed = sc.seed;
  sim::Simulation simulation(sc.world, d.robot, sc.start, params);
  std::optional<PointCloud> lidar;
  std::vector<DepthCloud> latest;
  while (simulation.now_s() < 2.0) {
    SensorFrame f = simulation.step(sc.command_at(simulation.now_s()));
    if (f.lidar) lidar = std::move(f.lidar);
    for (auto& c : f.depth) {
      d.depth_clouds.push_back(c.cloud);
      std::erase_if(latest, [&](const DepthCloud& l) { return l.camera == c.camera; });
      latest.push_back(std::move(c));
    }
  }
  d.frame.lidar = lidar;
  d.frame.depth = latest;
  return d;
}

nlohmann::json reduction_figures(const std::vector<PointCloud>& clouds) {
  perception::VoxelGrid grid;  // 0.02 m
  PointCloud out;
  double sum = 0.0;
  for (const auto& c : clouds) {
    grid.filter(c, out);
    sum += reduction_percent(finite_count(c), out.size());
  }
  return {{"depth_clouds", clouds.size()},
          {"leaf_m", 0.02},
          {"mean_reduction_percent", clouds.empty() ? 0.0 : sum / double(clouds.size())},
          {"thesis_reduction_percent", 91.07}};
}

// The same reduction on depth clouds simulated at another resolution (same scenario, seed, 2 s of
// walking, depth cameras only). The thesis does not state the D430 resolution it streamed; the
// simulated default is 424x240, 848x480 is Intel's recommended D4xx depth mode, and the reduction
// grows with the pixels per voxel.
nlohmann::json reduction_at_resolution(int width, int height) {
  const std::filesystem::path scenario = find_file("scenarios/digit_lab_static.yaml");
  const std::filesystem::path profile = find_file("config/digit.yaml");
  if (scenario.empty() || profile.empty()) return "scenarios/digit_lab_static.yaml or config/digit.yaml not found";
  const sim::Scenario sc = sim::load_scenario(scenario);
  const RobotProfile robot = io::load_robot_profile(profile);
  sim::SimulationParams params;
  params.seed = sc.seed;
  params.enable_lidar = false;
  params.depth.width = width;
  params.depth.height = height;
  sim::Simulation simulation(sc.world, robot, sc.start, params);
  std::vector<PointCloud> clouds;
  while (simulation.now_s() < 2.0) {
    SensorFrame f = simulation.step(sc.command_at(simulation.now_s()));
    for (auto& c : f.depth) clouds.push_back(std::move(c.cloud));
  }
  nlohmann::json j = reduction_figures(clouds);
  j["resolution"] = std::to_string(width) + "x" + std::to_string(height);
  return j;
}

}  // namespace

nlohmann::json run_perception_bench(const PerceptionBenchOptions& options) {
  const int reps = options.reps;
  nlohmann::json j;
  j["reps"] = reps;
  j["timing"] = "median thread CPU time (median_ms) and wall-clock time (median_wall_ms)";
  j["pcl_clouds"] = pcl_figures(reps);
  const DigitFrames d = simulated_digit_frames();
  j["digit_source"] = d.source;
  j["digit_depth_voxel_0.02"] =
      d.depth_clouds.empty() ? nlohmann::json("no depth cloud") : voxel_figures(d.depth_clouds.back(), 0.02, reps);
  j["digit_voxel_reduction"] = reduction_figures(d.depth_clouds);
  const sim::DepthCameraParams depth_defaults;
  j["digit_voxel_reduction"]["resolution"] =
      std::to_string(depth_defaults.width) + "x" + std::to_string(depth_defaults.height) + " (the simulated default)";
  j["digit_voxel_reduction_848x480"] = reduction_at_resolution(848, 480);
  j["digit_frame"] = frame_figures(d.frame, d.robot, reps);
  j["pcl_comparison"] =
      "not in this binary: build the opt-in target bipednav_bench_pcl (-DBIPEDNAV_BENCH_PCL=ON, "
      "needs libpcl-dev) for the ratios against pcl::VoxelGrid and pcl::SACSegmentation "
      "(bipednav_bench_pcl_gicp for GICP)";
  return j;
}

}  // namespace bipednav::bench
