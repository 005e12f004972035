#include "bench/closed_loop.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>

#include "bench/bench_runs.hpp"
#include "bench/route_report.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/navigation/navigation_server.hpp"
#include "bipednav/runner/footstep_runner.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/scenario_files.hpp"

namespace bipednav::bench {

namespace {

// One closed-loop run of the bench.
struct BenchRun {
  std::size_t scenario = 0;
  std::string robot;
  int seed = 0;
  runner::RunResult result;
  std::string error;  // what a run that threw said (it counts as failed)
};

// Every run: per scenario, per robot, the seeds.
std::vector<BenchRun> bench_runs(const ScenarioBenchOptions& a, std::size_t scenarios) {
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
// A humanoid (kind humanoid) walks the footstep loop (runner::run_footstep_scenario) with the
// footstep navigator's parameters; the others run the navigator.
void run_all(std::vector<BenchRun>& runs, const std::vector<sim::Scenario>& loaded, const runner::RunOptions& base,
             const std::map<std::string, RobotProfile>& profiles, int jobs) {
  run_in_parallel(runs.size(), jobs, "scenarios", [&](std::size_t i) {
    BenchRun& b = runs[i];
    try {
      const RobotProfile& robot = profiles.at(b.robot);
      if (runner::is_footstep_robot(robot)) {
        runner::FootstepRunOptions o;
        o.navigator = runner::footstep_navigator_params(robot, base.params_file);
        o.seed = static_cast<std::uint64_t>(b.seed);
        sim::Scenario s = loaded[b.scenario];
        s.robot = b.robot;
        b.result = runner::run_footstep_scenario(s, o).summary;
        return;
      }
      runner::RunOptions o = base;
      o.robot = b.robot;
      o.seed = static_cast<std::uint64_t>(b.seed);
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
nlohmann::json pair_row(const ScenarioBenchOptions& a, const std::vector<BenchRun>& runs, std::size_t first,
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

}  // namespace

nlohmann::json run_scenario_bench(const ScenarioBenchOptions& a) {
  require(a.jobs >= 1 && a.jobs <= 64, "--jobs", "in [1, 64]");
  require(!a.scenarios.empty() && !a.robots.empty(), "--scenarios/--robots", "not empty");
  std::vector<sim::Scenario> loaded;
  for (const auto& name : a.scenarios) loaded.push_back(sim::load_scenario(sim::resolve_scenario(name)));
  runner::RunOptions base;
  base.params_file = a.params;
  const std::map<std::string, RobotProfile> profiles = robot_profiles(a.robots, base);
  std::vector<BenchRun> runs = bench_runs(a, loaded.size());
  run_all(runs, loaded, base, profiles, a.jobs);
  nlohmann::json rows = nlohmann::json::array();
  std::size_t ok_total = 0, expected_total = 0;
  for (std::size_t first = 0; first < runs.size(); first += static_cast<std::size_t>(a.seeds)) {
    // The room the static world leaves the robot on its way (`bipednav route`): a pair with a margin
    // near or below zero fails by geometry, whatever the navigation does.
    constexpr double kRouteResolutionM = 0.01;
    const RobotProfile& robot = profiles.at(runs[first].robot);
    const nlohmann::json route = route_report(loaded[runs[first].scenario], robot, kRouteResolutionM);
    nlohmann::json row =
        pair_row(a, runs, first, profiles, pair_expectation(route, robot, base), ok_total, expected_total);
    row["route_margin_m"] = route["min_margin_m"];
    row["last_goal_margin_m"] = route["routes"].back()["margin_m"];
    rows.push_back(std::move(row));
  }
  return {{"rows", rows},        {"as_expected", expected_total}, {"succeeded", ok_total},
          {"runs", runs.size()}, {"first_seed", a.first_seed},    {"jobs", a.jobs}};
}

// Issue 8's real-time goal: the whole closed loop (simulator included) on one thread, `runs` times
// one after another; the real-time factor is simulated time over process CPU time (the run is
// single-threaded, so this is one core), medians over the runs against the 10x goal.
nlohmann::json run_loop_bench(const LoopBenchOptions& a) {
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
  for (const auto& [k, v] : stages) stage_median[k] = median(v);
  const double cpu_med = median(cpu_ms), wall_med = median(wall_ms);
  const double rtf = cpu_med > 0.0 ? last.time_s / (cpu_med * 1e-3) : 0.0;
  const double wall_rtf = wall_med > 0.0 ? last.time_s / (wall_med * 1e-3) : 0.0;
  constexpr double kGoalRtf = 10.0;
  return {{"scenario", last.scenario},
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
}

}  // namespace bipednav::bench
