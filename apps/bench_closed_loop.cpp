// `bipednav bench scenarios` (every scenario with N seeds, a success table) and `bipednav bench loop`
// (issue 8's real-time goal: the whole closed loop on one core).
#include "apps/bench_closed_loop.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>

#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "bench/bench_runs.hpp"
#include "bench/route_report.hpp"
#include "bipednav/navigation/navigation_server.hpp"
#include "bipednav/runner/footstep_runner.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/scenario_files.hpp"

namespace bipednav::app {

namespace {

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
  bench::run_in_parallel(runs.size(), jobs, "scenarios", [&](std::size_t i) {
    BenchRun& b = runs[i];
    runner::RunOptions o = base;
    o.robot = b.robot;
    o.seed = static_cast<std::uint64_t>(b.seed);
    try {
      b.result = runner::run_scenario(loaded[b.scenario], o);
    } catch (const std::exception& e) {
      b.error = e.what();
    }
  });
}

// What a pair should end with. Its last goal (the one a run is judged on) is infeasible when the
// widest route there keeps less room beyond footprint + sway (`route`) than the global planner's
// clearance allowance (ServerParams::plan_clearance_sigmas at the localizer's scan sigma): the planner
// sees the bottleneck closed, and the right end is to say so, NO_PATH_FOUND (or BLOCKED_GOAL for a
// goal too near an obstacle), before the time limit and without touching anything.
struct PairExpectation {
  double last_goal_margin_m = 0.0;  // +infinity without obstacles
  double allowance_m = 0.0;
  bool infeasible = false;
};

PairExpectation pair_expectation(const nlohmann::json& route, const RobotProfile& robot,
                                 const runner::RunOptions& base) {
  PairExpectation e;
  const auto& last = route["routes"].back();
  e.last_goal_margin_m =
      last["margin_m"].is_null() ? std::numeric_limits<double>::infinity() : last["margin_m"].get<double>();
  if (runner::is_footstep_robot(robot)) return e;  // the footstep navigator plans no clearance margin
  const navigation::NavigatorParams p = runner::navigator_params(robot, base);
  e.allowance_m = navigation::plan_clearance_allowance_m(p.server, p.localization.scan_position_sigma_m);
  e.infeasible = !last["connected"].get<bool>() || e.last_goal_margin_m < e.allowance_m;
  return e;
}

// Whether a run ended as its pair should: SUCCESS (judged strictly, RunResult::success), or for an
// infeasible pair NO_PATH_FOUND / BLOCKED_GOAL (get_path's or exe_path's) within a minute of simulated time (however
// long the scenario's time limit) with no contact.
bool as_expected(const BenchRun& b, const PairExpectation& e) {
  if (!b.error.empty()) return false;
  if (!e.infeasible) return b.result.success;
  constexpr double kGiveUpWithinS = 60.0;
  const Outcome o = b.result.outcome.outcome;
  const bool gave_up = o == Outcome::NO_PATH_FOUND || o == Outcome::BLOCKED_GOAL || o == Outcome::CTRL_BLOCKED_GOAL;
  return gave_up && b.result.time_s <= kGiveUpWithinS && b.result.collisions == 0;
}

// A failed run: its outcome, or what it threw.
nlohmann::json failure_json(const BenchRun& b) {
  return b.error.empty() ? nlohmann::json{{"seed", b.seed},
                                          {"outcome", std::string(outcome_name(b.result.outcome.outcome))},
                                          {"verdict", b.result.verdict},
                                          {"collisions", b.result.collisions},
                                          {"time_s", b.result.time_s},
                                          {"min_clearance_m", b.result.min_clearance_m}}
                         : nlohmann::json{{"seed", b.seed}, {"error", b.error}};
}

// The row of one scenario and robot: the --seeds runs from `first`; adds their successes to `ok_total`
// and the runs that ended as `expect` says to `expected_total`.
nlohmann::json pair_row(const BenchScenarioArgs& a, const std::vector<BenchRun>& runs, std::size_t first,
                        const std::map<std::string, RobotProfile>& profiles, const PairExpectation& expect,
                        std::size_t& ok_total, std::size_t& expected_total) {
  int ok = 0, expected = 0;
  double rtf = 0.0, sim_s = 0.0, max_s = 0.0;
  nlohmann::json failures = nlohmann::json::array();
  for (std::size_t i = first; i < first + static_cast<std::size_t>(a.seeds); ++i) {
    const BenchRun& b = runs[i];
    ok += b.error.empty() && b.result.success;
    rtf += b.result.real_time_factor / a.seeds;
    sim_s += b.result.time_s / a.seeds;
    max_s = std::max(max_s, b.result.time_s);
    if (as_expected(b, expect)) {
      ++expected;
      continue;
    }
    failures.push_back(failure_json(b));
  }
  ok_total += static_cast<std::size_t>(ok);
  expected_total += static_cast<std::size_t>(expected);
  return {{"scenario", a.scenarios[runs[first].scenario]},
          {"robot", profiles.at(runs[first].robot).name},
          {"expected_outcome", expect.infeasible ? "NO_PATH_FOUND/BLOCKED_GOAL" : "SUCCESS"},
          {"as_expected", expected},
          {"succeeded", ok},
          {"runs", a.seeds},
          {"mean_rtf", rtf},
          {"mean_time_s", sim_s},
          {"max_time_s", max_s},
          {"plan_clearance_allowance_m", expect.allowance_m},
          {"failures", failures}};
}

// The rows as a table: success count, mean real-time factor, the route's margin and the failed
// seeds of each pair.
void print_table(const nlohmann::json& rows) {
  std::printf("%-20s %-12s %-14s %9s %9s %9s  %s\n", "scenario", "robot", "expected", "as such", "RTF", "margin",
              "failed seeds");
  for (const auto& r : rows) {
    std::string failed;
    for (const auto& f : r["failures"]) {
      failed += (failed.empty() ? "" : ", ") + std::to_string(f["seed"].get<int>()) + " (" +
                (f.contains("error") ? std::string("error") : f["outcome"].get<std::string>()) +
                (f.contains("collisions") && f["collisions"].get<int>() > 0 ? ", collision"
                 : f.contains("outcome") && f["outcome"] == "SUCCESS"       ? ", off goal"
                                                                            : "") +
                ")";
    }
    const auto& margin = r["route_margin_m"];
    char margin_text[32] = "-";
    if (!margin.is_null()) std::snprintf(margin_text, sizeof margin_text, "%+.3f m", margin.get<double>());
    const std::string expected = r["expected_outcome"] == "SUCCESS" ? "SUCCESS" : "NO_PATH/BLOCKED";
    std::printf("%-20s %-12s %-14s %4d / %-3d %8.1fx %9s  %s\n", r["scenario"].get<std::string>().c_str(),
                r["robot"].get<std::string>().c_str(), expected.c_str(), r["as_expected"].get<int>(),
                r["runs"].get<int>(), r["mean_rtf"].get<double>(), margin_text, failed.c_str());
  }
}

void bench_scenarios(const BenchScenarioArgs& a) {
  require(a.jobs >= 1 && a.jobs <= 64, "--jobs", "in [1, 64]");
  require(!a.scenarios.empty() && !a.robots.empty(), "--scenarios/--robots", "not empty");
  std::vector<sim::Scenario> loaded;
  for (const auto& name : a.scenarios) loaded.push_back(sim::load_scenario(sim::resolve_scenario(name)));
  runner::RunOptions base;
  base.params_file = a.params;
  const std::map<std::string, RobotProfile> profiles = bench::robot_profiles(a.robots, base);
  std::vector<BenchRun> runs = bench_runs(a, loaded.size());
  run_all(runs, loaded, base, a.jobs);
  nlohmann::json rows = nlohmann::json::array();
  std::size_t ok_total = 0, expected_total = 0;
  for (std::size_t first = 0; first < runs.size(); first += static_cast<std::size_t>(a.seeds)) {
    // The room the static world leaves the robot on its way (`bipednav route`): a pair with a margin
    // near or below zero fails by geometry, whatever the navigation does.
    constexpr double kRouteResolutionM = 0.01;
    const RobotProfile& robot = profiles.at(runs[first].robot);
    const nlohmann::json route = bench::route_report(loaded[runs[first].scenario], robot, kRouteResolutionM);
    nlohmann::json row =
        pair_row(a, runs, first, profiles, pair_expectation(route, robot, base), ok_total, expected_total);
    row["route_margin_m"] = route["min_margin_m"];
    row["last_goal_margin_m"] = route["routes"].back()["margin_m"];
    rows.push_back(std::move(row));
  }
  if (a.json) {
    print_json({{"rows", rows},
                {"as_expected", expected_total},
                {"succeeded", ok_total},
                {"runs", runs.size()},
                {"first_seed", a.first_seed},
                {"jobs", a.jobs}});
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

// Issue 8's real-time goal: the whole closed loop (simulator included) on one thread, `runs` times
// one after another; the real-time factor is simulated time over process CPU time (the run is
// single-threaded, so this is one core), medians over the runs against the 10x goal.
// Returns whether the real-time factor meets its goal (the exit status).
bool bench_loop(const BenchLoopArgs& a) {
  require(a.runs >= 1, "--runs", ">= 1");
  const sim::Scenario s = sim::load_scenario(sim::resolve_scenario(a.scenario));
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
  for (const auto& [k, v] : stages) stage_median[k] = bench::median(v);
  const double cpu_med = bench::median(cpu_ms), wall_med = bench::median(wall_ms);
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
  print_figures(a.json, j, [&] {
    std::printf(
        "%s with %s: %s, %.1f s simulated; CPU median %.0f ms (%.0f-%.0f over %d runs): %.1fx real time "
        "(goal %.0fx: %s); wall %.1fx\n",
        last.scenario.c_str(), last.robot.c_str(), j["outcome"].get<std::string>().c_str(), last.time_s, cpu_med,
        j["cpu_min_ms"].get<double>(), j["cpu_max_ms"].get<double>(), a.runs, rtf, kGoalRtf,
        rtf >= kGoalRtf ? "met" : "not met", wall_rtf);
  });
  return bench_goals_met(j);
}

}  // namespace

void add_closed_loop_benches(CLI::App& bench) {
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
  add_json_flag(loop, lp->json);
  loop->add_option("--runs", lp->runs, "Runs, one after another (medians; default 3)")->check(CLI::Range(1, 100));
  loop->add_option("--robot", lp->robot, "Robot profile name or file (default: the scenario's)");
  loop->add_option("--params", lp->params, "Navigation parameters YAML (as `run --params`)");
  loop->callback([lp] { report_task(bench_loop(*lp)); });
}

}  // namespace bipednav::app
