#include "bench/global.hpp"

#include <filesystem>

#include "bench/movingai_runner.hpp"
#include "bench/replan_benchmark.hpp"

namespace bipednav::bench {

nlohmann::json run_global_bench(const GlobalBenchOptions& options) {
  using nlohmann::json;
  ReplanBenchParams p;
  p.max_replans = options.max_replans;
  const ReplanStats s = run_replan_benchmark(p);
  const double goal_exp = 10.0, goal_time = 5.0;
  json j = {{"world", "three_rooms 6 x 30 m at 0.1 m, obstacles revealed within 3 m"},
            {"replans", s.replans},
            {"reached_goal", s.reached_goal},
            {"travelled_m", s.travelled_m},
            {"changed_cells", s.changed_cells},
            {"cost_mismatches", s.cost_mismatches},
            {"first_plan_dstar_ms", s.first_dstar_ms},
            {"first_plan_astar_ms", s.first_astar_ms},
            {"first_plan_dstar_expansions", s.first_dstar_expansions},
            {"first_plan_astar_expansions", s.first_astar_expansions},
            {"replan_dstar_mean_expansions", s.dstar_mean_expansions},
            {"replan_astar_mean_expansions", s.astar_mean_expansions},
            {"replan_dstar_mean_ms", s.dstar_mean_ms},
            {"replan_astar_mean_ms", s.astar_mean_ms},
            {"replan_dstar_max_ms", s.dstar_max_ms},
            {"replan_astar_max_ms", s.astar_max_ms},
            {"expansions_ratio", s.expansions_ratio},
            {"goal_expansions_ratio", goal_exp},
            {"meets_goal_expansions_ratio", s.expansions_ratio >= goal_exp},
            {"replan_dstar_cpu_mean_ms", s.dstar_cpu_mean_ms},
            {"replan_astar_cpu_mean_ms", s.astar_cpu_mean_ms},
            {"time_ratio", s.time_ratio},
            {"cpu_time_ratio", s.cpu_time_ratio},
            {"goal_time_ratio", goal_time},
            {"meets_goal_time_ratio", s.cpu_time_ratio >= goal_time},
            {"timing", "the goal on thread CPU time (cpu_*); *_ms without cpu are wall time"}};
  const std::filesystem::path dir = find_movingai_dir(options.movingai_dir);
  if (dir.empty()) {
    j["movingai"] = nullptr;
    j["movingai_note"] = "tests/data/movingai not found; pass --movingai-dir";
  } else {
    // Relative to the working directory when below it (a record names no path of the machine).
    const std::filesystem::path rel = dir.lexically_relative(std::filesystem::current_path());
    const bool below = !rel.empty() && *rel.begin() != "..";
    j["movingai_dir"] = (below ? rel : dir).string();
    j["movingai"] = movingai_first_plans(dir);
  }
  return j;
}

}  // namespace bipednav::bench
