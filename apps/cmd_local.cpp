#include <iostream>
#include <nlohmann/json.hpp>

#include "apps/commands.hpp"
#include "bipednav/planning/local/bench_scene.hpp"

namespace bipednav::app {

namespace {

void bench_local(int cycles, int threads) {
  using namespace planning::local;
  nlohmann::json j;
  j["benchmark"] = "local";
  j["threads"] = threads;
  j["goal_median_ms"] = 10.0;
  j["goal_p99_ms"] = 25.0;
  for (const int n : {0, 20, 100}) {
    TebParams params;
    params.homotopy.enabled = true;
    params.homotopy.num_threads = threads;
    const auto st = run_local_bench(make_local_bench_scene(n, 42), params, cycles);
    nlohmann::json e;
    e["obstacles_placed"] = n;
    e["obstacles_extracted"] = st.obstacles;
    e["cycles"] = st.cycles;
    e["success_cycles"] = st.success_cycles;
    e["median_ms"] = st.median_ms;
    e["p99_ms"] = st.p99_ms;
    e["max_ms"] = st.max_ms;
    j["per_obstacle_count"].push_back(e);
    if (n == 100) {
      j["median_ms"] = st.median_ms;
      j["p99_ms"] = st.p99_ms;
      j["meets_goal_median"] = st.median_ms <= 10.0;
      j["meets_goal_p99"] = st.p99_ms <= 25.0;
    }
  }
  std::cout << j.dump(2) << std::endl;
}

}  // namespace

void add_local_commands(CLI::App& /*app*/, CLI::App& bench) {
  auto* b = bench.add_subcommand("local", "TEB local planner cycle time with 0, 20 and 100 obstacles");
  auto cycles = std::make_shared<int>(100);
  auto threads = std::make_shared<int>(1);
  auto json = std::make_shared<bool>(false);
  b->add_option("--cycles", *cycles, "control cycles per obstacle count")->check(CLI::PositiveNumber);
  b->add_option("--threads", *threads, "threads for the homotopy candidates")->check(CLI::PositiveNumber);
  b->add_flag("--json", *json, "print JSON (the only output format)");
  b->callback([cycles, threads] { bench_local(*cycles, *threads); });
}

}  // namespace bipednav::app
