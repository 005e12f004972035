// `bipednav run`: the closed loop in the simulator, `bipednav bench scenarios` and `bipednav params`
// (the effective navigation parameters as a file for --params).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "apps/cli_pose.hpp"
#include "apps/cmd_run_footsteps.hpp"
#include "apps/commands.hpp"
#include "bipednav/common/progress.hpp"
#include "bipednav/navigation/navigator_params_yaml.hpp"
#include "bipednav/runner/footstep_runner.hpp"
#include "bipednav/runner/replay_recorder.hpp"
#include "bipednav/runner/run_figure.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/sdf_world.hpp"
#include "bipednav/sim/world_drawing.hpp"
#include "bipednav/viz/replay_html.hpp"

#ifdef BIPEDNAV_WITH_ROSBAG
#include "ros/bag_recorder.hpp"
#endif

#ifndef BIPEDNAV_SOURCE_DIR
#define BIPEDNAV_SOURCE_DIR "."
#endif

namespace bipednav::app {

namespace {

std::filesystem::path scenario_dir() { return std::filesystem::path(BIPEDNAV_SOURCE_DIR) / "scenarios"; }

// "hexagon_static" or a path to a scenario file.
std::filesystem::path resolve_scenario(const std::string& name) {
  if (std::filesystem::exists(name)) return name;
  const auto p = scenario_dir() / (name + ".yaml");
  if (std::filesystem::exists(p)) return p;
  throw Error("no scenario '" + name + "' (neither a file nor scenarios/" + name + ".yaml)");
}

// A scenario around any Gazebo world file.
sim::Scenario scenario_from_world(const std::string& world_file, const std::string& robot, const std::string& start,
                                  const std::string& goal) {
  sim::Scenario s;
  const std::filesystem::path file(world_file);
  s.name = file.stem().string();
  s.world = sim::load_sdf_world(file, {file.parent_path() / "../models", scenario_dir() / "worlds"});
  s.robot = robot.empty() ? "turtlebot3" : robot;
  s.start = parse_pose(start, "--start");
  s.goals = {{0.0, parse_pose(goal, "--goal")}};
  s.time_limit_s = 180.0;
  const sim::Bounds2 b = sim::world_bounds(s.world);
  s.bounds = {std::min({b.min_x_m, s.start.x, s.goals[0].pose.x}), std::min({b.min_y_m, s.start.y, s.goals[0].pose.y}),
              std::max({b.max_x_m, s.start.x, s.goals[0].pose.x}), std::max({b.max_y_m, s.start.y, s.goals[0].pose.y})};
  s.validate();
  return s;
}

nlohmann::json to_json(const runner::RunResult& r) {
  nlohmann::json j;
  j["scenario"] = r.scenario;
  j["robot"] = r.robot;
  j["success"] = r.success;
  j["outcome"] = std::string(outcome_name(r.outcome.outcome));
  j["outcome_code"] = code(r.outcome.outcome);
  j["message"] = r.outcome.message;
  j["collisions"] = r.collisions;
  if (r.first_collision) {
    j["first_collision"] = {{"time_s", r.first_collision->time_s},
                            {"x_m", r.first_collision->point.x()},
                            {"y_m", r.first_collision->point.y()},
                            {"obstacle", r.first_collision->obstacle}};
  }
  j["time_s"] = r.time_s;
  j["path_length_m"] = r.path_length_m;
  j["min_clearance_m"] = r.min_clearance_m;
  j["goal_error_m"] = r.goal_error_m;
  j["goal_error_rad"] = r.goal_error_rad;
  j["localization_error_m"] = r.localization_error_m;
  j["replans"] = r.replans;
  j["recoveries"] = r.recoveries;
  j["recovery_log"] = nlohmann::json::array();
  for (const auto& rec : r.recovery_log)
    j["recovery_log"].push_back({{"name", rec.name},
                                 {"start_s", rec.start_s},
                                 {"end_s", rec.end_s},
                                 {"outcome", std::string(outcome_name(rec.result.outcome))},
                                 {"outcome_code", code(rec.result.outcome)},
                                 {"message", rec.result.message}});
  j["real_time_factor"] = r.real_time_factor;
  j["wall_s"] = r.wall_s;
  j["cpu_s"] = r.cpu_s;
  j["cpu_real_time_factor"] = r.cpu_real_time_factor;
  j["stage_cpu_ms"] = r.stage_cpu_ms;
  j["goals_given"] = r.goals_given;
  const sim::FaultCounters& f = r.faults;
  j["faults"] = {{"sweeps_dropped", f.sweeps_dropped},     {"depth_points_nan", f.depth_points_nan},
                 {"odometry_jumps", f.odometry_jumps},     {"odometry_slipped", f.odometry_slipped},
                 {"messages_delayed", f.messages_delayed}, {"messages_reordered", f.messages_reordered},
                 {"commands_dropped", f.commands_dropped}};
  j["watchdog_stops"] = r.watchdog_stops;
  j["watchdog_stopped_s"] = r.watchdog_stopped_s;
  return j;
}

void print_summary(const runner::RunResult& r) {
  std::printf("%s with %s: %s (%s%s%s)\n", r.scenario.c_str(), r.robot.c_str(), r.success ? "SUCCESS" : "FAILED",
              std::string(outcome_name(r.outcome.outcome)).c_str(), r.outcome.message.empty() ? "" : ": ",
              r.outcome.message.c_str());
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
  std::string world, start = "0,0,0", goal, bag, replay, trace;
  runner::RunOptions options;
  std::vector<std::string> faults;  // type:start_s:duration_s[:value]
  std::uint64_t seed = 0;
  double time_limit_s = 0.0;
};

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

void run_command(const RunArgs& a) {
  const sim::Scenario s = a.world.empty() ? sim::load_scenario(resolve_scenario(a.scenario))
                                          : scenario_from_world(a.world, a.options.robot, a.start, a.goal);
  if (runs_by_footsteps(s, a.options.robot)) {  // humanoids walk by footsteps (apps/cmd_run_footsteps.cpp)
    reject_wheeled_only_options(a);
    return run_footsteps_command(s, a.options.robot, a.out, a.seed, a.time_limit_s, a.options.params_file, a.replay);
  }
  runner::RunOptions o = a.options;
  if (a.seed) o.seed = a.seed;
  if (a.time_limit_s > 0) o.time_limit_s = a.time_limit_s;
  o.progress = true;
  for (const auto& f : a.faults) o.faults.push_back(sim::parse_fault(f));
#ifdef BIPEDNAV_WITH_ROSBAG
  std::shared_ptr<ros1::BagRecorder> bag;
  if (!a.bag.empty()) {
    bag = std::make_shared<ros1::BagRecorder>(a.bag, runner::load_robot(o.robot.empty() ? s.robot : o.robot));
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
#ifdef BIPEDNAV_WITH_ROSBAG
  if (bag) {
    bag->close();
    std::printf("  recorded %zu messages to %s\n", bag->messages(), a.bag.c_str());
  }
#endif
  std::filesystem::create_directories(a.out);
  const auto dir = std::filesystem::path(a.out);
  std::ofstream(dir / "run.json") << to_json(r).dump(2) << "\n";
  runner::write_run_figure(dir / "run.png", s, r);
  if (!a.trace.empty()) write_trace_csv(a.trace, r.trace);
  print_summary(r);
  std::printf("  wrote %s and %s\n", (dir / "run.json").c_str(), (dir / "run.png").c_str());
  if (replay) {
    viz::write_replay_html(a.replay, replay->finish(r));
    std::printf("  wrote %s (%zu frames)\n", a.replay.c_str(), replay->frames().size());
  }
}

struct BenchScenarioArgs {
  int seeds = 1;
  int first_seed = 1;  // seeds first_seed .. first_seed + seeds - 1 (fresh-seed screens)
  int jobs = 1;
  std::vector<std::string> robots{"turtlebot3", "digit"};
  std::vector<std::string> scenarios{"hexagon_static",   "hexagon_dynamic",   "three_rooms",
                                     "digit_lab_static", "digit_lab_dynamic", "turtlebot3_world"};
  bool json = false;
  std::string params;  // navigation parameters file (RunOptions::params_file)
};

// One closed-loop run of the bench.
struct BenchRun {
  std::size_t scenario = 0;
  std::string robot;
  int seed = 0;
  runner::RunResult result;
  std::string error;  // what a run that threw said (it counts as failed)
};

// Each robot's name in the table (a profile file's robot by its profile name), after reading its
// navigation parameters: a bad parameters file is reported once here, not as every run's error.
std::map<std::string, std::string> robot_names(const std::vector<std::string>& robots, const runner::RunOptions& base) {
  std::map<std::string, std::string> names;
  for (const auto& robot : robots) {
    const RobotProfile profile = runner::load_robot(robot);
    runner::navigator_params(profile, base);
    names[robot] = profile.name;
  }
  return names;
}

// Every run: per scenario, per robot, the seeds.
std::vector<BenchRun> bench_runs(const BenchScenarioArgs& a, std::size_t scenarios) {
  std::vector<BenchRun> runs;
  for (std::size_t k = 0; k < scenarios; ++k)
    for (const auto& robot : a.robots)
      for (int i = 0; i < a.seeds; ++i) {
        BenchRun& b = runs.emplace_back();
        b.scenario = k;
        b.robot = robot;
        b.seed = a.first_seed + i;
      }
  return runs;
}

// Runs are independent simulations: --jobs of them at a time, each on one thread. The results do
// not depend on --jobs; a run's real-time factor is its own wall time, so it drops when the
// jobs share cores.
void run_all(std::vector<BenchRun>& runs, const std::vector<sim::Scenario>& loaded, const runner::RunOptions& base,
             int jobs) {
  ProgressBar bar("scenarios", runs.size(), true);
  std::mutex bar_mutex;
  std::atomic<std::size_t> next{0}, done{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < runs.size(); i = next++) {
      BenchRun& b = runs[i];
      runner::RunOptions o = base;
      o.robot = b.robot;
      o.seed = static_cast<std::uint64_t>(b.seed);
      try {
        b.result = runner::run_scenario(loaded[b.scenario], o);
      } catch (const std::exception& e) {
        b.error = e.what();
      }
      const std::lock_guard lock(bar_mutex);
      bar.update(++done);
    }
  };
  std::vector<std::thread> threads;
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
  bar.finish();
}

// A failed run: its outcome, or what it threw.
nlohmann::json failure_json(const BenchRun& b) {
  return b.error.empty() ? nlohmann::json{{"seed", b.seed},
                                          {"outcome", std::string(outcome_name(b.result.outcome.outcome))},
                                          {"collisions", b.result.collisions},
                                          {"time_s", b.result.time_s},
                                          {"min_clearance_m", b.result.min_clearance_m}}
                         : nlohmann::json{{"seed", b.seed}, {"error", b.error}};
}

// The row of one scenario and robot: the --seeds runs from `first`; adds their successes to `ok_total`.
nlohmann::json pair_row(const BenchScenarioArgs& a, const std::vector<BenchRun>& runs, std::size_t first,
                        const std::map<std::string, std::string>& robot_names, std::size_t& ok_total) {
  int ok = 0;
  double rtf = 0.0, sim_s = 0.0;
  nlohmann::json failures = nlohmann::json::array();
  for (std::size_t i = first; i < first + static_cast<std::size_t>(a.seeds); ++i) {
    const BenchRun& b = runs[i];
    const bool success = b.error.empty() && b.result.success;
    ok += success;
    rtf += b.result.real_time_factor / a.seeds;
    sim_s += b.result.time_s / a.seeds;
    if (success) continue;
    failures.push_back(failure_json(b));
  }
  ok_total += static_cast<std::size_t>(ok);
  return {{"scenario", a.scenarios[runs[first].scenario]},
          {"robot", robot_names.at(runs[first].robot)},
          {"succeeded", ok},
          {"runs", a.seeds},
          {"mean_rtf", rtf},
          {"mean_time_s", sim_s},
          {"failures", failures}};
}

// The rows as a table: success count, mean real-time factor and the failed seeds of each pair.
void print_table(const nlohmann::json& rows) {
  std::printf("%-20s %-12s %9s %9s  %s\n", "scenario", "robot", "success", "RTF", "failed seeds");
  for (const auto& r : rows) {
    std::string failed;
    for (const auto& f : r["failures"]) {
      failed += (failed.empty() ? "" : ", ") + std::to_string(f["seed"].get<int>()) + " (" +
                (f.contains("error") ? std::string("error") : f["outcome"].get<std::string>()) +
                (f.contains("collisions") && f["collisions"].get<int>() > 0 ? ", collision" : "") + ")";
    }
    std::printf("%-20s %-12s %4d / %-3d %8.1fx  %s\n", r["scenario"].get<std::string>().c_str(),
                r["robot"].get<std::string>().c_str(), r["succeeded"].get<int>(), r["runs"].get<int>(),
                r["mean_rtf"].get<double>(), failed.c_str());
  }
}

void bench_scenarios(const BenchScenarioArgs& a) {
  require(a.jobs >= 1 && a.jobs <= 64, "--jobs", "in [1, 64]");
  require(!a.scenarios.empty() && !a.robots.empty(), "--scenarios/--robots", "not empty");
  std::vector<sim::Scenario> loaded;
  for (const auto& name : a.scenarios) loaded.push_back(sim::load_scenario(resolve_scenario(name)));
  runner::RunOptions base;
  base.params_file = a.params;
  const std::map<std::string, std::string> names = robot_names(a.robots, base);
  std::vector<BenchRun> runs = bench_runs(a, loaded.size());
  run_all(runs, loaded, base, a.jobs);
  nlohmann::json rows = nlohmann::json::array();
  std::size_t ok_total = 0;
  for (std::size_t first = 0; first < runs.size(); first += static_cast<std::size_t>(a.seeds))
    rows.push_back(pair_row(a, runs, first, names, ok_total));
  if (a.json) {
    std::printf("%s\n", nlohmann::json{{"rows", rows},
                                       {"succeeded", ok_total},
                                       {"runs", runs.size()},
                                       {"first_seed", a.first_seed},
                                       {"jobs", a.jobs}}
                            .dump(2)
                            .c_str());
    return;
  }
  print_table(rows);
}

struct BenchLoopArgs {
  std::string scenario = "hexagon_static";
  std::string robot;  // empty: the scenario's
  int runs = 3;
  std::string params;  // navigation parameters file (RunOptions::params_file)
  bool json = false;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

// Issue 8's real-time goal: the whole closed loop (simulator included) on one thread, `runs` times
// one after another; the real-time factor is simulated time over process CPU time (the run is
// single-threaded, so this is one core), medians over the runs against the 10x goal.
void bench_loop(const BenchLoopArgs& a) {
  require(a.runs >= 1, "--runs", ">= 1");
  const sim::Scenario s = sim::load_scenario(resolve_scenario(a.scenario));
  runner::RunOptions o;
  o.robot = a.robot;
  o.params_file = a.params;
  std::vector<double> cpu_ms, wall_ms;
  std::map<std::string, std::vector<double>> stages;
  runner::RunResult last;
  for (int i = 0; i < a.runs; ++i) {
    last = runner::run_scenario(s, o);
    cpu_ms.push_back(last.cpu_s * 1e3);
    wall_ms.push_back(last.wall_s * 1e3);
    for (const auto& [k, v] : last.stage_cpu_ms) stages[k].push_back(v);
  }
  nlohmann::json stage_median = nlohmann::json::object();
  for (const auto& [k, v] : stages) stage_median[k] = median(v);
  const double cpu_med = median(cpu_ms), wall_med = median(wall_ms);
  const double rtf = cpu_med > 0.0 ? last.time_s / (cpu_med * 1e-3) : 0.0;
  const double wall_rtf = wall_med > 0.0 ? last.time_s / (wall_med * 1e-3) : 0.0;
  constexpr double kGoalRtf = 10.0;
  const nlohmann::json j{{"scenario", last.scenario},
                         {"robot", last.robot},
                         {"runs", a.runs},
                         {"success", last.success},
                         {"outcome", std::string(outcome_name(last.outcome.outcome))},
                         {"simulated_s", last.time_s},
                         {"cpu_median_ms", cpu_med},
                         {"cpu_min_ms", *std::min_element(cpu_ms.begin(), cpu_ms.end())},
                         {"cpu_max_ms", *std::max_element(cpu_ms.begin(), cpu_ms.end())},
                         {"wall_median_ms", wall_med},
                         {"cpu_real_time_factor_rtf", rtf},
                         {"wall_real_time_factor_rtf", wall_rtf},
                         {"stage_cpu_median_ms", stage_median},
                         {"goal_rtf", kGoalRtf},
                         {"meets_goal", rtf >= kGoalRtf}};
  if (!a.json) {
    std::printf(
        "%s with %s: %s, %.1f s simulated; CPU median %.0f ms (%.0f-%.0f over %d runs): %.1fx real time "
        "(goal %.0fx: %s); wall %.1fx\n",
        last.scenario.c_str(), last.robot.c_str(), j["outcome"].get<std::string>().c_str(), last.time_s, cpu_med,
        j["cpu_min_ms"].get<double>(), j["cpu_max_ms"].get<double>(), a.runs, rtf, kGoalRtf,
        rtf >= kGoalRtf ? "met" : "not met", wall_rtf);
    return;
  }
  std::printf("%s\n", j.dump(2).c_str());
}

struct ParamsArgs {
  std::string robot = "turtlebot3";
  std::string params;
};

// A humanoid's (kind humanoid) are the footstep navigator's, in its own layout.
void print_params(const ParamsArgs& a) {
  runner::RunOptions o;
  o.params_file = a.params;
  const RobotProfile robot = runner::load_robot(a.robot);
  const bool footsteps = runner::is_footstep_robot(robot);
  const std::string yaml = footsteps
                               ? navigation::navigator_params_yaml(runner::footstep_navigator_params(o.params_file))
                               : navigation::navigator_params_yaml(runner::navigator_params(robot, o));
  std::printf("# bipednav %snavigation parameters for robot %s%s: every key is optional; read with --params FILE\n%s",
              footsteps ? "footstep " : "", a.robot.c_str(), a.params.empty() ? "" : (" with " + a.params).c_str(),
              yaml.c_str());
}

}  // namespace

void add_run_commands(CLI::App& app, CLI::App& bench) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* run = app.add_subcommand("run", "Navigate a scenario closed-loop in the built-in simulator");
  run->add_option("scenario", args->scenario, "Scenario name (scenarios/NAME.yaml) or file")->capture_default_str();
  run->add_option("--out", args->out, "Output directory for run.json and run.png")->capture_default_str();
  run->add_option("--robot", args->options.robot,
                  "Robot profile: a name in config/ (turtlebot3, digit, nao) or your own profile FILE.yaml "
                  "(config/README.md); overrides the scenario's");
  run->add_option("--seed", args->seed, "Seed (overrides the scenario's)");
  run->add_option("--time-limit", args->time_limit_s, "Time limit in simulated seconds");
  run->add_option("--localization", args->options.localization, "loam or odometry");
  run->add_option("--local-planner", args->options.local_planner, "teb or tracker");
  run->add_option("--global-planner", args->options.global_planner, "dstar_lite or astar");
  run->add_option("--params", args->options.params_file,
                  "Navigation parameters YAML overlaid on the robot's defaults (`bipednav params` prints the layout; "
                  "a humanoid's is the footstep navigator's); "
                  "--localization/--local-planner/--global-planner and the scenario's goal tolerances win");
  run->add_option("--world", args->world, "A Gazebo .world file instead of a scenario");
  run->add_option("--start", args->start, "With --world: start pose x,y,yaw")->capture_default_str();
  run->add_option("--goal", args->goal, "With --world: goal pose x,y,yaw");
  run->add_option(
      "--fault", args->faults,
      "Inject a fault: type:start_s:duration_s[:value] (lidar_dropout, depth_nan_burst, localization_jump "
      "(value dx,dy,dyaw), odometry_slip, stale_timestamps, out_of_order_timestamps, goal_flood, command_dropout); "
      "repeatable");
  run->add_option("--bag", args->bag, "Record the run as a rosbag (ROS build only)");
  run->add_option("--replay", args->replay, "Write a self-contained HTML replay of the run to this file");
  run->add_option("--trace", args->trace,
                  "Write the 10 Hz trace (true and estimated pose, command, active tree leaf) to this CSV file");
  run->callback([args] {
    if (!args->world.empty() && args->goal.empty()) throw Error("--world needs --goal x,y,yaw");
    run_command(*args);
  });

  auto b = std::make_shared<BenchScenarioArgs>();
  CLI::App* sc = bench.add_subcommand("scenarios", "Run every scenario with N seeds and both robots");
  sc->add_option("--seeds", b->seeds, "Seeds per scenario and robot")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  sc->add_option("--first-seed", b->first_seed, "The first seed: runs seeds first .. first + N - 1")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  sc->add_option("--robots", b->robots, "Robot profiles (names in config/ or profile files)")->capture_default_str();
  sc->add_option("--scenarios", b->scenarios, "Scenario names or files")->capture_default_str();
  sc->add_option("--jobs", b->jobs, "Runs at a time, each on one thread (results do not depend on it)")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  sc->add_flag("--json", b->json, "Print one JSON object (with the failed seeds of each pair)");
  sc->add_option("--params", b->params, "Navigation parameters YAML for every run (as `run --params`)");
  sc->callback([b] { bench_scenarios(*b); });

  auto lp = std::make_shared<BenchLoopArgs>();
  CLI::App* loop = bench.add_subcommand(
      "loop", "The whole closed loop's real-time factor on one core (simulated / process CPU time; goal 10x)");
  loop->add_option("scenario", lp->scenario, "Scenario name or file")->capture_default_str();
  loop->add_flag("--json", lp->json, "Print one JSON object");
  loop->add_option("--runs", lp->runs, "Runs, one after another (medians; default 3)")->check(CLI::Range(1, 100));
  loop->add_option("--robot", lp->robot, "Robot profile name or file (default: the scenario's)");
  loop->add_option("--params", lp->params, "Navigation parameters YAML (as `run --params`)");
  loop->callback([lp] { bench_loop(*lp); });

  auto pa = std::make_shared<ParamsArgs>();
  CLI::App* params = app.add_subcommand(
      "params", "Print the effective navigation parameters as YAML (the layout of --params; like ros2 param dump)");
  params
      ->add_option("--robot", pa->robot, "Robot profile name or file (a humanoid: the footstep navigator's parameters)")
      ->capture_default_str();
  params->add_option("--params", pa->params, "A parameters file to overlay first (prints the result)");
  params->callback([pa] { print_params(*pa); });
}

}  // namespace bipednav::app
