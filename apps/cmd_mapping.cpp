#include <algorithm>
#include <cstdio>
#include <ctime>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_inflation.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_output.hpp"
#include "apps/commands.hpp"
#include "bench/mapping_scene.hpp"
#include "bipednav/common/clock.hpp"
#include "bipednav/common/cpu_time.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/mapping/global_costmap.hpp"
#include "bipednav/mapping/heightmap_fusion.hpp"
#include "bipednav/mapping/local_costmap.hpp"
#include "bipednav/mapping/map_io.hpp"
#include "bipednav/viz/costmap_png.hpp"

namespace bipednav::app {

namespace {

using namespace bipednav::mapping;

struct InflateOptions {
  std::string map;
  InflationFlags inflation;  // the global costmap's defaults
  std::string out_png, out_yaml;
  int scale = 1;
};

nlohmann::json cost_counts(const Costmap2D& m) {
  const auto n = [&](auto pred) { return std::count_if(m.data().begin(), m.data().end(), pred); };
  return {{"free", n([](auto v) { return v == kFree; })},
          {"inflated", n([](auto v) { return v > kFree && v < kInscribed; })},
          {"inscribed", n([](auto v) { return v == kInscribed; })},
          {"lethal", n([](auto v) { return v == kLethal; })},
          {"unknown", n([](auto v) { return v == kUnknown; })}};
}

nlohmann::json geometry_json(const GridGeometry& g) {
  return {{"width_cells", g.width},
          {"height_cells", g.height},
          {"resolution_m", g.resolution_m},
          {"origin_x_m", g.origin_x_m},
          {"origin_y_m", g.origin_y_m}};
}

void run_inflate(const InflateOptions& o) {
  if (!o.out_png.empty()) prepare_output_file(o.out_png, "--out");
  if (!o.out_yaml.empty()) prepare_output_file(o.out_yaml, "--yaml");
  const Costmap2D map = mapping::read_map_server(o.map);
  const GlobalCostmapParams p = o.inflation.params(map.resolution_m());
  Stopwatch sw;
  GlobalCostmap global(map.geometry(), p);
  global.set_occupancy(map);
  const double ms = sw.elapsed_ms();
  if (!o.out_png.empty()) viz::write_costmap_png(o.out_png, global.costmap(), o.scale);
  if (!o.out_yaml.empty()) mapping::write_map_server(o.out_yaml, global.costmap());
  nlohmann::json j = {{"map", o.map},
                      {"geometry", geometry_json(map.geometry())},
                      {"inflate_ms", ms},
                      {"costs", cost_counts(global.costmap())}};
  if (!o.out_png.empty()) j["png"] = o.out_png;
  if (!o.out_yaml.empty()) j["yaml"] = o.out_yaml;
  print_json(j);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
double maximum(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }

// Returns whether the benchmark met its goals (the exit status).
bool run_bench(int iterations) {
  // Local costmap: the robot walks 5 cm per update through the room, one full frame each time.
  std::vector<SyntheticFrame> frames;
  for (int i = 0; i < std::min(iterations, 40); ++i)
    frames.push_back(synthetic_digit_frame({-1.0 + 0.05 * i, 0.2, 0.1 * i}));
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
  const nlohmann::json j = {{"iterations", iterations},
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
  print_json(j);
  return bench_goals_met(j);
}

}  // namespace

void add_mapping_commands(CLI::App& app, CLI::App& bench) {
  CLI::App* costmap = app.add_subcommand("costmap", "Costmap tools (map_server maps)");
  costmap->require_subcommand(1);

  auto info_map = std::make_shared<std::string>();
  CLI::App* info = costmap->add_subcommand("info", "Print a map_server map's geometry and cost counts as JSON");
  info->add_option("map", *info_map, "map_server YAML")->required()->check(CLI::ExistingFile);
  accept_json_flag(info);
  info->callback([info_map] {
    const Costmap2D m = mapping::read_map_server(*info_map);
    print_json({{"map", *info_map}, {"geometry", geometry_json(m.geometry())}, {"costs", cost_counts(m)}});
  });

  auto o = std::make_shared<InflateOptions>();
  CLI::App* inflate = costmap->add_subcommand("inflate", "Inflate a map_server map and write PNG / map_server files");
  inflate->add_option("map", o->map, "map_server YAML")->required()->check(CLI::ExistingFile);
  o->inflation.add_to(inflate);
  inflate->add_option("--out", o->out_png, "PNG to write");
  inflate->add_option("--scale", o->scale, "PNG pixels per cell")
      ->capture_default_str()
      ->check(check::integer_at_least(1));
  inflate->add_option("--yaml", o->out_yaml, "map_server YAML (+ PGM) to write");
  accept_json_flag(inflate);
  inflate->callback([o] { run_inflate(*o); });

  auto iterations = std::make_shared<int>(100);
  CLI::App* b = bench.add_subcommand("mapping", "Local costmap update, inflation and heightmap timings");
  accept_json_flag(b);
  b->add_option("--iterations", *iterations, "updates to time (1..10000)")
      ->capture_default_str()
      ->check(check::integer_in(1, 10000));
  b->callback([iterations] { report_task(run_bench(*iterations)); });
}

}  // namespace bipednav::app
