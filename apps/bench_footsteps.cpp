// `bipednav bench footsteps`: the second reference's Table I on random cluttered heightmaps; the
// harness is bench/footsteps.
#include "apps/bench_footsteps.hpp"

#include <memory>
#include <nlohmann/json.hpp>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "bench/footsteps.hpp"

namespace bipednav::app {

namespace {

// Prints the figures; returns whether the benchmark met its goals (the exit status).
bool bench_footsteps(const bench::FootstepBenchOptions& a) {
  const nlohmann::json j = bench::run_footstep_bench(a);
  print_json(j);
  return bench_goals_met(j);
}

}  // namespace

void add_footstep_bench(CLI::App& bench) {
  auto b = std::make_shared<bench::FootstepBenchOptions>();
  CLI::App* bf = bench.add_subcommand("footsteps", "Table I of the footstep reference on random heightmaps");
  bf->add_option("--maps", b->maps, "Random 2.5 x 2.5 m heightmaps")
      ->capture_default_str()
      ->check(check::integer_at_least(1));
  bf->add_option("--problems", b->problems, "Start/goal pairs in all (the reference: 100)")
      ->capture_default_str()
      ->check(check::integer_at_least(1));
  bf->add_option("--optimal-limit", b->optimal_limit_s, "Time cap of the optimal reference search, s")
      ->capture_default_str()
      ->check(check::positive());
  bf->add_option("--short-limit", b->short_limit_s, "The shorter ARA* time limit, s")
      ->capture_default_str()
      ->check(check::positive());
  bf->add_option("--long-limit", b->long_limit_s, "The longer ARA* time limit, s")
      ->capture_default_str()
      ->check(check::positive());
  bf->add_option("--jobs", b->jobs, "Problems searched in parallel (each on one thread)")
      ->capture_default_str()
      ->check(check::integer_in(1, 64));
  bf->add_option("--clock", b->clock, "Clock of the time limits and times: thread_cpu (load-independent) or wall")
      ->capture_default_str()
      ->check(CLI::IsMember({"thread_cpu", "wall"}));
  bf->add_option("--log", b->log, "Also write each finished problem as a JSON line to this file");
  bf->add_option("--only-map", b->only_map, "Run only this map's problems (0-based; diagnosis)")
      ->check(check::integer_at_least(0));
  bf->add_option("--only-problem", b->only_problem, "Run only this problem index within each map (0-based)")
      ->check(check::integer_at_least(0));
  bf->add_option("--optimal-from", b->optimal_from,
                 "Take the optimal reference costs from a previous results JSON (per_problem) or --log .jsonl "
                 "file instead of searching them (rows must have the same start/goal)");
  bf->add_option("--heuristics", b->heuristics, "Comma-separated ARA* heuristics to run")->capture_default_str();
  bf->add_flag("--skip-planar", b->skip_planar, "Do not run the planar-footsteps-only baseline");
  accept_json_flag(bf);
  bf->callback([b] { report_task(bench_footsteps(*b)); });
}

}  // namespace bipednav::app
