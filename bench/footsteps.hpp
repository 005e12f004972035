#pragma once

#include <nlohmann/json.hpp>
#include <string>

// `bipednav bench footsteps`: the second reference's Table I on random cluttered heightmaps.
namespace bipednav::bench {

struct FootstepBenchOptions {
  int maps = 10, problems = 10, jobs = 1, only_map = -1, only_problem = -1;
  double long_limit_s = 10.0, short_limit_s = 5.0, optimal_limit_s = 120.0;
  std::string clock = "thread_cpu", log, optimal_from, heuristics = "dijkstra,euclidean";
  bool skip_planar = false;
};

// Generates the seeded heightmaps and start/goal problems, then searches each problem (`jobs` at a
// time, each on one thread) with the optimal reference (unless taken from `optimal_from`), ARA*
// with each heuristic up to the longer time limit and the planar-only baseline (unless
// `skip_planar`); writes each finished problem to `log` as a JSON line when given. Returns the
// settings, the table (suboptimality, time to a first solution and solve rate per heuristic and
// time limit, aggregated in problem order), the goals and whether they are met (`meets_goal_*`)
// and every problem; throws Error for bad options or files.
nlohmann::json run_footstep_bench(const FootstepBenchOptions& options);

}  // namespace bipednav::bench
