// `bipednav run`: the closed loop in the simulator, and `bipednav params` (the effective navigation
// parameters as a file for --params); the closed-loop benches are in bench_closed_loop.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/bench_closed_loop.hpp"
#include "apps/bench_worlds.hpp"
#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_output.hpp"
#include "apps/cli_world.hpp"
#include "apps/cmd_run_footsteps.hpp"
#include "apps/commands.hpp"
#include "bipednav/io/number_list.hpp"
#include "bipednav/navigation/navigator_params_yaml.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/footstep_runner.hpp"
#include "bipednav/runner/replay_recorder.hpp"
#include "bipednav/runner/run_figure.hpp"
#include "bipednav/runner/run_json.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/placement_check.hpp"
#include "bipednav/sim/scenario_files.hpp"
#include "bipednav/viz/replay_html.hpp"

#ifdef BIPEDNAV_WITH_ROSBAG
#include "ros/bag_recorder.hpp"
#endif

#ifndef BIPEDNAV_SOURCE_DIR
#define BIPEDNAV_SOURCE_DIR "."
#endif

namespace bipednav::app {

namespace {

// `outputs`: the files written (run_json, run_png, and bag, replay_html, trace_csv when asked for).
void print_summary(const runner::RunResult& r, const nlohmann::json& outputs) {
  if (r.success)
    std::printf("%s with %s: SUCCESS (goal reached at t = %.1f s, nothing touched)\n", r.scenario.c_str(),
                r.robot.c_str(), r.time_s);
  else
    std::printf("%s with %s: FAILED (%s)\n", r.scenario.c_str(), r.robot.c_str(), r.verdict.c_str());
  // A success the navigator qualifies (a weak position estimate at the goal) shows its words.
  if (r.outcome.ok() && r.outcome.message.find(';') != std::string::npos)
    std::printf("  navigator: %s\n", r.outcome.message.c_str());
  std::printf("  time %.1f s, path %.2f m, min clearance %.3f m, collisions %d\n", r.time_s, r.path_length_m,
              r.min_clearance_m, r.collisions);
  std::printf("  goal error %.3f m / %.3f rad, localization error %.3f m\n", r.goal_error_m, r.goal_error_rad,
              r.localization_error_m);
  std::printf("  replans %zu, recoveries %zu, real-time factor %.1fx (wall), %.1fx (CPU: %.2f s)\n", r.replans,
              r.recoveries, r.real_time_factor, r.cpu_real_time_factor, r.cpu_s);
  if (!r.recovery_log.empty()) {
    // Each recovery and outcome with its count, in the order they first happened.
    std::vector<std::pair<std::string, int>> counts;
    for (const auto& rec : r.recovery_log) {
      const std::string key =
          rec.name + " " + (rec.running() ? std::string("RUNNING") : std::string(outcome_name(rec.result.outcome)));
      auto it = std::find_if(counts.begin(), counts.end(), [&](const auto& c) { return c.first == key; });
      if (it == counts.end())
        counts.emplace_back(key, 1);
      else
        ++it->second;
    }
    std::string line;
    for (const auto& [key, n] : counts) line += (line.empty() ? "" : ", ") + key + " x" + std::to_string(n);
    std::printf("  recovery outcomes: %s\n", line.c_str());
  }
  if (r.watchdog_stops > 0)
    std::printf("  walking controller's watchdog stopped the robot %zu time(s), %.1f s in all (no commands)\n",
                r.watchdog_stops, r.watchdog_stopped_s);
  std::string stages;
  for (const auto& [name, ms] : r.stage_cpu_ms)
    stages += (stages.empty() ? "" : ", ") + name + " " + std::to_string(static_cast<long>(std::lround(ms)));
  std::printf("  CPU ms per stage: %s\n", stages.c_str());
  if (outputs.contains("bag"))
    std::printf("  recorded %zu messages to %s\n", outputs["bag_messages"].get<std::size_t>(),
                outputs["bag"].get<std::string>().c_str());
  std::printf("  wrote %s and %s\n", outputs["run_json"].get<std::string>().c_str(),
              outputs["run_png"].get<std::string>().c_str());
  if (outputs.contains("trace_csv")) std::printf("  wrote %s\n", outputs["trace_csv"].get<std::string>().c_str());
  if (outputs.contains("replay_html"))
    std::printf("  wrote %s (%zu frames)\n", outputs["replay_html"].get<std::string>().c_str(),
                outputs["replay_frames"].get<std::size_t>());
}

// The run's 10 Hz trace as CSV: true and estimated pose, command and the behavior tree's active leaf.
void write_trace_csv(const std::filesystem::path& file, const std::vector<runner::TraceSample>& trace) {
  std::ofstream out(file);
  if (!out) throw Error("cannot write " + file.string());
  out << "t_s,x_m,y_m,yaw_rad,est_x_m,est_y_m,est_yaw_rad,cmd_vx_mps,cmd_vy_mps,cmd_wz_radps,active_leaf\n";
  char row[320];
  for (const auto& t : trace) {
    std::snprintf(row, sizeof row, "%.2f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,", t.t_s, t.true_pose.x,
                  t.true_pose.y, t.true_pose.theta, t.estimated_pose.x, t.estimated_pose.y, t.estimated_pose.theta,
                  t.cmd.linear_x, t.cmd.linear_y, t.cmd.angular_z);
    out << row << t.active_leaf << "\n";
  }
}

struct RunArgs {
  std::string scenario = "hexagon_static";
  std::string out = "out";
  std::string world, start, goal, bag, replay, trace;
  std::string goal_tolerance;  // "M,RAD" (empty: the scenario's)
  runner::RunOptions options;
  std::vector<std::string> faults;  // type:start_s:duration_s[:value]
  std::optional<std::uint64_t> seed;
  std::optional<double> time_limit_s;
  bool quiet = false;
  bool json = false;
};

// Every output is checked before the run (a run takes minutes), and every start and goal: one
// inside an obstacle or off the map is reported now, in metres, not after a minute of recoveries.
RobotProfile check_before_run(const RunArgs& a, const sim::Scenario& s, bool footsteps) {
  prepare_output_dir(a.out, "--out");
  if (!a.trace.empty()) prepare_output_file(a.trace, "--trace");
  if (!a.replay.empty()) prepare_output_file(a.replay, "--replay");
  if (!a.bag.empty()) prepare_output_file(a.bag, "--bag");
  const RobotProfile robot = navigation::load_robot(a.options.robot.empty() ? s.robot : a.options.robot);
  sim::check_placements(s, robot, !footsteps);
  return robot;
}

// The footstep loop has its own localization (GICP-corrected odometry) and planner (ARA* footsteps),
// no LiDAR stack to fault and no 10 Hz command trace or rosbag: these options would be ignored.
void reject_wheeled_only_options(const RunArgs& a) {
  std::string unused;
  const auto check = [&](bool set, const char* name) {
    if (set) unused += std::string(unused.empty() ? "" : ", ") + name;
  };
  check(!a.options.localization.empty(), "--localization");
  check(!a.options.local_planner.empty(), "--local-planner");
  check(!a.options.global_planner.empty(), "--global-planner");
  check(!a.faults.empty(), "--fault");
  check(!a.bag.empty(), "--bag");
  check(!a.trace.empty(), "--trace");
  if (!unused.empty())
    throw Error("a humanoid's footstep run does not take " + unused +
                " (it has its own localization and footstep planner; --params sets them)");
}

// The run's verdict for the exit status (0 / 1): the runner's success (goal reached by the navigator
// and by the true pose, no collision).
bool run_succeeded(const runner::RunResult& r) { return r.success; }

// --goal-tolerance M,RAD: two positive numbers.
void apply_goal_tolerance(const std::string& text, sim::Scenario& s) {
  if (text.empty()) return;
  const std::vector<double> v = io::parse_number_list(text);
  if (v.size() != 2 || !(v[0] > 0.0 && v[1] > 0.0))
    throw Error("--goal-tolerance: expected M,RAD (two positive numbers: metres, radians), got '" + text + "'");
  s.goal_tolerance_m = v[0];
  s.goal_tolerance_rad = v[1];
}

bool run_command(const RunArgs& a) {
  sim::Scenario s = a.world.empty() ? sim::load_scenario(sim::resolve_scenario(a.scenario))
                                    : scenario_from_world(a.world, a.options.robot, a.start, a.goal);
  apply_goal_tolerance(a.goal_tolerance, s);
  const bool footsteps = runs_by_footsteps(s, a.options.robot);
  if (footsteps) reject_wheeled_only_options(a);
  const RobotProfile robot = check_before_run(a, s, footsteps);
  if (footsteps)  // humanoids walk by footsteps (apps/cmd_run_footsteps.cpp)
    return run_footsteps_command(s, a.options.robot, a.out, {a.seed, a.time_limit_s, !a.quiet, a.json},
                                 a.options.params_file, a.replay);
  runner::RunOptions o = a.options;
  if (a.seed) o.seed = a.seed;
  if (a.time_limit_s) o.time_limit_s = a.time_limit_s;
  o.progress = !a.quiet;
  for (const auto& f : a.faults) {
    try {
      o.faults.push_back(sim::parse_fault(f));
    } catch (const Error& e) {
      throw Error("--fault " + f + ": " + e.what());
    }
  }
#ifdef BIPEDNAV_WITH_ROSBAG
  std::shared_ptr<ros1::BagRecorder> bag;
  if (!a.bag.empty()) {
    bag = std::make_shared<ros1::BagRecorder>(a.bag, navigation::load_robot(o.robot.empty() ? s.robot : o.robot));
    o.render_unused_depth = true;  // the bag keeps every depth image
    o.on_step = [bag](const sim::Simulation& sim, const SensorFrame& f, const navigation::Navigator& n,
                      const Twist& c) { bag->record(sim, f, n, c); };
  }
#else
  if (!a.bag.empty()) throw Error("--bag needs the ROS build (scripts/install-deps --ros, then rebuild)");
#endif
  std::unique_ptr<runner::ReplayRecorder> replay;
  if (!a.replay.empty()) {
    replay = std::make_unique<runner::ReplayRecorder>(s);
    replay->attach(o);
  }
  const runner::RunResult r = runner::run_scenario(s, o);
  const auto dir = std::filesystem::path(a.out);
  nlohmann::json j = runner::run_result_json(r);
  std::ofstream(dir / "run.json") << j.dump(2) << "\n";
  runner::write_run_figure(dir / "run.png", s, r, runner::navigator_params(robot, o).server.local_planner);
  j["outputs"] = {{"run_json", (dir / "run.json").string()}, {"run_png", (dir / "run.png").string()}};
  if (!a.trace.empty()) {
    write_trace_csv(a.trace, r.trace);
    j["outputs"]["trace_csv"] = a.trace;
  }
#ifdef BIPEDNAV_WITH_ROSBAG
  if (bag) {
    bag->close();
    j["outputs"]["bag"] = a.bag;
    j["outputs"]["bag_messages"] = bag->messages();
  }
#endif
  if (replay) {
    viz::write_replay_html(a.replay, replay->finish(r));
    j["outputs"]["replay_html"] = a.replay;
    j["outputs"]["replay_frames"] = replay->frames().size();
  }
  print_figures(a.json, j, [&] { print_summary(r, j["outputs"]); });
  return run_succeeded(r);
}

struct ParamsArgs {
  std::string robot = "turtlebot3";
  std::string params;
};

// The navigation parameters of a wheeled robot or walker; a file in the footstep layout is reported as such.
navigation::NavigatorParams wheeled_params_for_cli(const RobotProfile& robot, const runner::RunOptions& o) {
  try {
    return runner::navigator_params(robot, o);
  } catch (const FileError& e) {
    throw Error(std::string(e.what()) + " (robot " + robot.name + ", kind " + robot.kind +
                ", reads the wheeled navigator's layout, not a humanoid's: `bipednav params --robot " + robot.name +
                "` prints it)");
  }
}

// The compiled-in behavior tree is an absolute path of this machine: a dump leaves it out (the
// default), so the file is the same on every machine and reads back to the same parameters.
std::string without_default_tree(std::string yaml, const std::string& default_tree) {
  const std::string line = "behavior_tree: " + default_tree + "\n";
  const auto at = yaml.find(line);
  if (at != std::string::npos)
    yaml.replace(at, line.size(),
                 "# behavior_tree: the built-in config/behavior_trees/navigate.xml (give a file to use another)\n");
  return yaml;
}

// A humanoid's (kind humanoid) are the footstep navigator's, in its own layout.
void print_params(const ParamsArgs& a) {
  runner::RunOptions o;
  o.params_file = a.params;
  const RobotProfile robot = navigation::load_robot(a.robot);
  const bool footsteps = runner::is_footstep_robot(robot);
  const std::string yaml =
      footsteps ? navigation::navigator_params_yaml(footstep_params_for_cli(robot, o.params_file))
                : without_default_tree(navigation::navigator_params_yaml(wheeled_params_for_cli(robot, o)),
                                       navigation::NavigatorParams::for_robot(robot).behavior_tree);
  std::printf("# bipednav %snavigation parameters for robot %s%s: every key is optional; read with --params FILE\n%s",
              footsteps ? "footstep " : "", a.robot.c_str(), a.params.empty() ? "" : (" with " + a.params).c_str(),
              yaml.c_str());
}

}  // namespace

void add_run_commands(CLI::App& app, CLI::App& bench) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* run = app.add_subcommand("run", "Navigate a scenario closed-loop in the built-in simulator");
  CLI::Option* scenario =
      run->add_option("scenario", args->scenario, "Scenario name (scenarios/NAME.yaml) or file")->capture_default_str();
  run->add_option("--out", args->out, "Output directory for run.json and run.png")->capture_default_str();
  run->add_option("--robot", args->options.robot,
                  "Robot profile: a name in config/ (turtlebot3, digit, nao) or your own profile FILE.yaml "
                  "(config/README.md); overrides the scenario's");
  run->add_option("--seed", args->seed, "Seed, a whole number >= 0 (overrides the scenario's)")
      ->check(check::integer_at_least(0));
  run->add_option("--time-limit", args->time_limit_s, "Time limit in simulated seconds (overrides the scenario's)")
      ->check(check::positive());
  run->add_option("--localization", args->options.localization, "loam or odometry")
      ->check(CLI::IsMember({"loam", "odometry"}));
  run->add_option("--local-planner", args->options.local_planner, "teb or tracker")
      ->check(CLI::IsMember({"teb", "tracker"}));
  run->add_option("--global-planner", args->options.global_planner, "dstar_lite or astar")
      ->check(CLI::IsMember({"dstar_lite", "astar"}));
  run->add_option("--params", args->options.params_file,
                  "Navigation parameters YAML overlaid on the robot's defaults (`bipednav params` prints the layout; "
                  "a humanoid's is the footstep navigator's); "
                  "--localization/--local-planner/--global-planner and the scenario's goal tolerances win")
      ->check(CLI::ExistingFile);
  add_world_options(run, scenario, args->world, args->start, args->goal);
  run->add_option("--goal-tolerance", args->goal_tolerance,
                  "Goal tolerances M,RAD: the true pose must end within them (overrides the scenario's; "
                  "default with --world 0.2,0.2)");
  run->add_option(
      "--fault", args->faults,
      "Inject a fault: type:start_s:duration_s[:value] (lidar_dropout, depth_nan_burst, localization_jump "
      "(value dx,dy,dyaw), odometry_slip, stale_timestamps, out_of_order_timestamps, goal_flood, command_dropout); "
      "repeatable");
  run->add_option("--bag", args->bag, "Record the run as a rosbag (ROS build only)");
  run->add_option("--replay", args->replay, "Write a self-contained HTML replay of the run to this file");
  run->add_option("--trace", args->trace,
                  "Write the 10 Hz trace (true and estimated pose, command, active tree leaf) to this CSV file");
  run->add_flag("--quiet", args->quiet, "No progress bar (it is shown only when stderr is a terminal)");
  add_json_flag(run, args->json);
  run->callback([args] { report_task(run_command(*args)); });

  add_closed_loop_benches(bench);
  add_world_benches(bench);

  auto pa = std::make_shared<ParamsArgs>();
  CLI::App* params = app.add_subcommand(
      "params", "Print the effective navigation parameters as YAML (the layout of --params; like ros2 param dump)");
  params
      ->add_option("--robot", pa->robot, "Robot profile name or file (a humanoid: the footstep navigator's parameters)")
      ->capture_default_str();
  params->add_option("--params", pa->params, "A parameters file to overlay first (prints the result)")
      ->check(CLI::ExistingFile);
  params->callback([pa] { print_params(*pa); });
}

}  // namespace bipednav::app
