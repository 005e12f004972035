// `bipednav bench sim --json`: the simulator's speed; the harness is bench/sim_speed.
#include "apps/bench_sim.hpp"

#include <memory>
#include <nlohmann/json.hpp>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "bench/sim_speed.hpp"

namespace bipednav::app {
namespace {

struct BenchOptions {
  bench::SimBenchOptions options;
  bool json = false;
};

// Prints the figures; returns whether the benchmark met its goal (the exit status).
bool run_sim_bench(BenchOptions o) {
  o.options.progress = !o.json;
  const nlohmann::json j = bench::run_sim_bench(o.options);
  print_json(j);
  return bench_goals_met(j);
}

}  // namespace

void add_sim_bench(CLI::App& bench) {
  auto opts = std::make_shared<BenchOptions>();
  CLI::App* cmd = bench.add_subcommand("sim", "Simulator speed: Digit's LiDAR + two depth cameras, one core");
  cmd->add_option("--duration", opts->options.duration_s, "simulated seconds")
      ->capture_default_str()
      ->check(check::positive());
  cmd->add_option("--robot", opts->options.robot_file, "robot profile YAML (default: built-in Digit)");
  cmd->add_option("--sensors", opts->options.sensors, "which sensors run")
      ->check(CLI::IsMember({"all", "lidar", "depth"}))
      ->capture_default_str();
  cmd->add_option("--renderer", opts->options.renderer,
                  "depth images: z-buffer (raster) or one ray per pixel (raycast)")
      ->check(CLI::IsMember({"raster", "raycast"}))
      ->capture_default_str();
  cmd->add_flag("--json", opts->json, "print only the JSON result (no progress)");
  cmd->callback([opts] { report_task(run_sim_bench(*opts)); });
}

}  // namespace bipednav::app
