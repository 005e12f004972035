// `bipednav cloud filter|segment` and `bipednav bench perception`.
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_output.hpp"
#include "apps/commands.hpp"
#include "bench/synthetic_scene.hpp"
#include "bipednav/common/clock.hpp"
#include "bipednav/common/cpu_time.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/io/ply.hpp"
#include "bipednav/io/robot_profile_yaml.hpp"
#include "bipednav/perception/ground_segmentation.hpp"
#include "bipednav/perception/pass_through.hpp"
#include "bipednav/perception/pipeline.hpp"
#include "bipednav/perception/voxel_grid.hpp"
#include "bipednav/sim/scenario.hpp"
#include "bipednav/sim/simulation.hpp"

namespace bipednav::app {
namespace {

namespace fs = std::filesystem;
using perception::PassThroughParams;

PointCloud read_cloud(const fs::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".ply") return io::read_ply(file);
  if (ext == ".pcd") return io::read_pcd(file);
  throw Error(file.string() + ": unknown point cloud format (expected .pcd or .ply)");
}

struct BandOptions {
  double range_m = std::numeric_limits<double>::infinity();
  double zmin = -std::numeric_limits<double>::infinity();
  double zmax = std::numeric_limits<double>::infinity();

  void add_to(CLI::App* c) {
    c->add_option("--range", range_m, "keep points within this distance of the origin [m]")->check(check::positive());
    c->add_option("--zmin", zmin, "keep points with z >= this [m]")->check(check::finite());
    c->add_option("--zmax", zmax, "keep points with z <= this [m]")->check(check::finite());
  }
  // The pass-through's parameters; throws Error naming the option at fault (--zmin above --zmax).
  PassThroughParams params() const {
    PassThroughParams p;
    p.max_range_m = range_m;
    p.min_height_m = zmin;
    p.max_height_m = zmax;
    with_flag_names({{"max_range_m", "--range"}, {"min_height_m", "--zmin"}, {"max_height_m", "--zmax"}},
                    [&] { p.validate(); });
    return p;
  }
};

struct FilterOptions {
  std::string in, out, encoding = "binary_compressed";
  double voxel_m = 0.0;
  BandOptions band;
  bool json = false;
};

void run_filter(const FilterOptions& o) {
  const io::PcdEncoding encoding = io::pcd_encoding_from_string(o.encoding);
  const PassThroughParams band = o.band.params();
  prepare_output_file(o.out, "OUT");
  const PointCloud in = read_cloud(o.in);
  const Stopwatch sw;
  PointCloud out = perception::pass_through(in, band);
  const std::size_t after_band = out.size();
  if (o.voxel_m > 0.0) {
    perception::VoxelGridParams v;
    v.leaf_size_m.setConstant(o.voxel_m);
    out = perception::voxel_downsample(out, v);
  }
  const double ms = sw.elapsed_ms();
  io::write_pcd(o.out, out, encoding);
  const bool voxel = o.voxel_m > 0.0;
  const nlohmann::json j = {{"file", o.in},
                            {"points", in.size()},
                            {"after_pass_through", after_band},
                            {"voxel_m", voxel ? nlohmann::json(o.voxel_m) : nlohmann::json(nullptr)},
                            {"after_voxel_grid", voxel ? nlohmann::json(out.size()) : nlohmann::json(nullptr)},
                            {"time_ms", ms},
                            {"out", o.out}};
  print_figures(o.json, j, [&] {
    if (voxel)
      std::printf("%s: %zu points, %zu after the pass-through, %zu after the voxel grid (%.2f ms) -> %s\n",
                  o.in.c_str(), in.size(), after_band, out.size(), ms, o.out.c_str());
    else
      std::printf("%s: %zu points, %zu after the pass-through, no voxel grid (%.2f ms) -> %s\n", o.in.c_str(),
                  in.size(), after_band, ms, o.out.c_str());
  });
}

struct SegmentOptions {
  std::string in;
  perception::RansacParams ransac;
  std::uint64_t seed = 1;
  bool json = false;
  BandOptions band;
};

// Returns whether a plane was found (the exit status).
bool run_segment(SegmentOptions o) {
  with_flag_names({{"distance_threshold_m", "--threshold"},
                   {"success_probability", "--probability"},
                   {"max_iterations", "--max-iterations"}},
                  [&] { o.ransac.validate(); });
  const PointCloud in = perception::pass_through(read_cloud(o.in), o.band.params());
  Rng rng(o.seed);
  const Stopwatch sw;
  const perception::PlaneFit fit = perception::fit_plane_ransac(in.points, o.ransac, rng);
  const double ms = sw.elapsed_ms();
  nlohmann::json j;
  j["file"] = o.in;
  j["found"] = fit.found;
  j["plane"] = {fit.plane[0], fit.plane[1], fit.plane[2], fit.plane[3]};
  j["inliers"] = fit.inliers;
  j["points"] = in.size();
  j["distance_threshold_m"] = o.ransac.distance_threshold_m;
  j["inlier_std_m"] = fit.inlier_std_m;
  j["iterations"] = fit.iterations;
  j["time_ms"] = ms;
  print_figures(o.json, j, [&] {
    if (!fit.found)
      std::printf("no plane found in %s (%zu points after the filter)\n", o.in.c_str(), in.size());
    else
      std::printf("plane %.6f %.6f %.6f %.6f, %zu of %zu points within %.3f m, %.2f ms\n", fit.plane[0], fit.plane[1],
                  fit.plane[2], fit.plane[3], fit.inliers, in.size(), o.ransac.distance_threshold_m, ms);
  });
  return fit.found;
}

void add_filter(CLI::App& cloud) {
  auto o = std::make_shared<FilterOptions>();
  CLI::App* c = cloud.add_subcommand("filter", "Pass-through / range filter and voxel grid; writes a PCD");
  c->add_option("IN", o->in, "input cloud (.pcd or .ply)")->required()->check(CLI::ExistingFile);
  c->add_option("OUT", o->out, "output .pcd")->required();
  c->add_option("--voxel", o->voxel_m, "voxel leaf size [m] (0: no voxel grid)")
      ->capture_default_str()
      ->check(check::non_negative());
  o->band.add_to(c);
  c->add_option("--encoding", o->encoding, "ascii, binary or binary_compressed")
      ->capture_default_str()
      ->check(CLI::IsMember({"ascii", "binary", "binary_compressed"}));
  add_json_flag(c, o->json);
  c->callback([o] { run_filter(*o); });
}

void add_segment(CLI::App& cloud) {
  auto o = std::make_shared<SegmentOptions>();
  CLI::App* c = cloud.add_subcommand("segment", "RANSAC plane fit (eq. 4.1-4.4)");
  c->add_option("IN", o->in, "input cloud (.pcd or .ply)")->required()->check(CLI::ExistingFile);
  c->add_option("--threshold", o->ransac.distance_threshold_m, "inlier distance [m]")
      ->capture_default_str()
      ->check(check::positive());
  c->add_option("--probability", o->ransac.success_probability, "desired success probability (eq. 4.4)")
      ->capture_default_str()
      ->check(check::open_range(0.0, 1.0));
  c->add_option("--max-iterations", o->ransac.max_iterations, "cap on the iteration count")
      ->capture_default_str()
      ->check(check::integer_at_least(1));
  c->add_flag("--normal-prior", o->ransac.use_normal_prior, "only accept planes within 15 deg of horizontal");
  c->add_option("--seed", o->seed, "RANSAC seed, a whole number >= 0")
      ->capture_default_str()
      ->check(check::integer_at_least(0));
  o->band.add_to(c);
  add_json_flag(c, o->json);
  c->callback([o] { report_task(run_segment(*o)); });
}

// ---- bench perception -------------------------------------------------------------------------
// Times are thread CPU time (the machine may be shared; the goals are "on one core"), median of
// --reps runs; wall-clock medians are given next to them.

// Looks for <rel>, tests/data/<rel> or shared/data/<rel> above the working directory and the executable.
fs::path find_file(const std::string& rel) {
  std::error_code ec;
  for (fs::path dir : {fs::current_path(), fs::read_symlink("/proc/self/exe", ec).parent_path()}) {
    for (int up = 0; up < 6 && !dir.empty(); ++up, dir = dir.parent_path()) {
      for (const fs::path& c : {dir / rel, dir / "tests" / "data" / rel, dir / "shared" / "data" / rel})
        if (fs::exists(c)) return c;
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
  const fs::path table = find_file("pcl/table_scene_mug_stereo_textured.pcd");
  const fs::path plane = find_file("pcl/sac_plane_test.pcd");
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
  const fs::path scenario = find_file("scenarios/digit_lab_static.yaml");
  const fs::path profile = find_file("config/digit.yaml");
  if (scenario.empty() || profile.empty()) {
    d.source = "synthetic (scenarios/digit_lab_static.yaml or config/digit.yaml not found)";
    d.robot = perception::synthetic_digit_profile();
    d.frame = perception::synthetic_digit_frame(d.robot);
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
  const fs::path scenario = find_file("scenarios/digit_lab_static.yaml");
  const fs::path profile = find_file("config/digit.yaml");
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

// Returns whether the benchmark met its goals (the exit status).
bool run_perception_bench(int reps) {
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
  print_json(j);
  return bench_goals_met(j);
}

void add_perception_bench(CLI::App& bench) {
  auto reps = std::make_shared<int>(15);
  CLI::App* c = bench.add_subcommand("perception", "Voxel grid, RANSAC and the Digit frame pipeline timings");
  c->add_option("--reps", *reps, "repetitions per figure (median reported)")
      ->capture_default_str()
      ->check(check::integer_in(1, 1000));
  accept_json_flag(c);
  c->callback([reps] { report_task(run_perception_bench(*reps)); });
}

}  // namespace

void add_cloud_commands(CLI::App& app, CLI::App& bench) {
  CLI::App* cloud = app.add_subcommand("cloud", "Point cloud tools (filter, segment)");
  cloud->require_subcommand(1);
  add_filter(*cloud);
  add_segment(*cloud);
  add_perception_bench(bench);
}

}  // namespace bipednav::app
