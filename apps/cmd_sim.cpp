// `bipednav sim SCENARIO`: drives the robot of a scenario open-loop (its scripted commands, or a
// slow straight line) through the built-in simulator (runner/open_loop_run) and writes a top-view
// figure and a summary.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/bench_sim.hpp"
#include "apps/cli_checks.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_output.hpp"
#include "apps/cmd_route.hpp"
#include "apps/commands.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/open_loop_run.hpp"
#include "bipednav/sim/scenario.hpp"
#include "bipednav/sim/scenario_files.hpp"

namespace bipednav::app {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct SimOptions {
  std::string scenario;
  double duration_s = 30.0;
  std::string out_dir = "out";
  std::string robot;       // empty: the scenario's
  std::string config_dir;  // robot profiles (empty: the installed config/)
  double step_s = 0.01;
  bool quiet = false;
  bool json = false;
};

void run_sim_command(const SimOptions& opt) {
  const fs::path scenario_file = sim::resolve_scenario(opt.scenario);
  const sim::Scenario scenario = sim::load_scenario(scenario_file);
  const RobotProfile robot = navigation::load_robot(opt.robot.empty() ? scenario.robot : opt.robot, opt.config_dir);
  const fs::path out(opt.out_dir);
  prepare_output_dir(out, "--out");
  sim::SimulationParams params;
  params.step_s = opt.step_s;
  params.seed = scenario.seed;
  with_flag_names({{"step_s", "--step"}}, [&] { params.validate(); });
  runner::OpenLoopOptions run;
  run.duration_s = opt.duration_s;
  run.progress = !opt.quiet;
  json j = runner::run_open_loop(scenario, robot, params, run, out / "sim.png");
  std::ofstream json_file(out / "sim.json");
  json_file << j.dump(2) << "\n";
  if (!json_file) throw FileError((out / "sim.json").string(), "", "cannot write the summary");
  j["outputs"] = {{"sim_png", (out / "sim.png").string()}, {"sim_json", (out / "sim.json").string()}};
  print_figures(opt.json, j, [&] {
    std::printf("%s: %.1f s simulated (%.0fx real time), %.2f m driven, %zu collision(s); wrote %s and %s\n",
                scenario.name.c_str(), j["duration_s"].get<double>(), j["real_time_factor"].get<double>(),
                j["distance_m"].get<double>(), j["collision_count"].get<std::size_t>(), (out / "sim.png").c_str(),
                (out / "sim.json").c_str());
  });
}

}  // namespace

void add_sim_commands(CLI::App& app, CLI::App& bench) {
  auto opt = std::make_shared<SimOptions>();
  CLI::App* cmd =
      app.add_subcommand("sim",
                         "Drive a scenario's robot open-loop (scripted commands or a straight line) in the simulator; "
                         "writes OUT/sim.png and OUT/sim.json");
  cmd->add_option("scenario", opt->scenario, "Scenario name (scenarios/NAME.yaml) or file")->required();
  cmd->add_option("--duration", opt->duration_s, "Simulated time in seconds")
      ->capture_default_str()
      ->check(check::positive());
  cmd->add_option("--out", opt->out_dir, "Output directory")->capture_default_str();
  cmd->add_option(
      "--robot", opt->robot,
      "Robot profile: a name in config/ or a profile FILE.yaml (config/README.md); overrides the scenario's");
  cmd->add_option("--config-dir", opt->config_dir, "Directory of robot profiles (default: the installed config/)");
  cmd->add_option("--step", opt->step_s, "Simulation step in seconds")->capture_default_str()->check(check::positive());
  cmd->add_flag("--quiet", opt->quiet, "No progress bar (it is shown only when stderr is a terminal)");
  add_json_flag(cmd, opt->json);
  cmd->callback([opt] { run_sim_command(*opt); });
  add_sim_bench(bench);
  add_route_command(app);
}

}  // namespace bipednav::app
