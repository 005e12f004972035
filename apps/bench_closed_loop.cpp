// `bipednav bench scenarios` (every scenario with N seeds, a success table) and `bipednav bench loop`
// (issue 8's real-time goal: the whole closed loop on one core); the harnesses are bench/closed_loop.
#include "apps/bench_closed_loop.hpp"

#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "bench/closed_loop.hpp"

namespace bipednav::app {

namespace {

struct BenchScenarioArgs {
  bench::ScenarioBenchOptions options;
  bool json = false;
};

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
  const nlohmann::json j = bench::run_scenario_bench(a.options);
  if (a.json) {
    print_json(j);
    return;
  }
  print_table(j["rows"]);
}

struct BenchLoopArgs {
  bench::LoopBenchOptions options;
  bool json = false;
};

// Returns whether the real-time factor meets its goal (the exit status).
bool bench_loop(const BenchLoopArgs& a) {
  const nlohmann::json j = bench::run_loop_bench(a.options);
  print_figures(a.json, j, [&] {
    std::printf(
        "%s with %s: %s, %.1f s simulated; CPU median %.0f ms (%.0f-%.0f over %d runs): %.1fx real time "
        "(goal %.0fx: %s); wall %.1fx\n",
        j["scenario"].get<std::string>().c_str(), j["robot"].get<std::string>().c_str(),
        j["outcome"].get<std::string>().c_str(), j["simulated_s"].get<double>(), j["cpu_median_ms"].get<double>(),
        j["cpu_min_ms"].get<double>(), j["cpu_max_ms"].get<double>(), j["runs"].get<int>(),
        j["cpu_real_time_factor_rtf"].get<double>(), j["goal_rtf"].get<double>(),
        j["meets_goal"].get<bool>() ? "met" : "not met", j["wall_real_time_factor_rtf"].get<double>());
  });
  return bench_goals_met(j);
}

}  // namespace

void add_closed_loop_benches(CLI::App& bench) {
  auto b = std::make_shared<BenchScenarioArgs>();
  CLI::App* sc = bench.add_subcommand("scenarios", "Run every scenario with N seeds and both robots");
  sc->add_option("--seeds", b->options.seeds, "Seeds per scenario and robot")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  sc->add_option("--first-seed", b->options.first_seed, "The first seed: runs seeds first .. first + N - 1")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  sc->add_option("--robots", b->options.robots, "Robot profiles (names in config/ or profile files)")
      ->capture_default_str();
  sc->add_option("--scenarios", b->options.scenarios, "Scenario names or files")->capture_default_str();
  sc->add_option("--jobs", b->options.jobs, "Runs at a time, each on one thread (results do not depend on it)")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  sc->add_flag("--json", b->json, "Print one JSON object (with the failed seeds of each pair)");
  sc->add_option("--params", b->options.params, "Navigation parameters YAML for every run (as `run --params`)");
  sc->callback([b] { bench_scenarios(*b); });

  auto lp = std::make_shared<BenchLoopArgs>();
  CLI::App* loop = bench.add_subcommand(
      "loop", "The whole closed loop's real-time factor on one core (simulated / process CPU time; goal 10x)");
  loop->add_option("scenario", lp->options.scenario, "Scenario name or file")->capture_default_str();
  add_json_flag(loop, lp->json);
  loop->add_option("--runs", lp->options.runs, "Runs, one after another (medians; default 3)")
      ->check(CLI::Range(1, 100));
  loop->add_option("--robot", lp->options.robot, "Robot profile name or file (default: the scenario's)");
  loop->add_option("--params", lp->options.params, "Navigation parameters YAML (as `run --params`)");
  loop->callback([lp] { report_task(bench_loop(*lp)); });
}

}  // namespace bipednav::app
