// `bipednav costmap info|inflate` and `bipednav bench mapping` (the harness is bench/mapping).
#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_inflation.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_output.hpp"
#include "apps/commands.hpp"
#include "bench/mapping.hpp"
#include "bipednav/common/clock.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/mapping/global_costmap.hpp"
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

// Prints the figures; returns whether the benchmark met its goals (the exit status).
bool bench_mapping(const bench::MappingBenchOptions& o) {
  const nlohmann::json j = bench::run_mapping_bench(o);
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

  auto bo = std::make_shared<bench::MappingBenchOptions>();
  CLI::App* b = bench.add_subcommand("mapping", "Local costmap update, inflation and heightmap timings");
  accept_json_flag(b);
  b->add_option("--iterations", bo->iterations, "updates to time (1..10000)")
      ->capture_default_str()
      ->check(check::integer_in(1, 10000));
  b->callback([bo] { report_task(bench_mapping(*bo)); });
}

}  // namespace bipednav::app
