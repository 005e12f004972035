#include "bench/footsteps.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numeric>
#include <thread>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/common/progress.hpp"
#include "bipednav/planning/footstep/footstep_planner.hpp"
#include "bipednav/planning/footstep/terrain_generator.hpp"

namespace bipednav::bench {

namespace {

using namespace planning::footstep;

// Mean, standard deviation and median.
nlohmann::json stats(std::vector<double> v) {
  if (v.empty()) return {{"mean", nullptr}, {"std", nullptr}, {"median", nullptr}, {"n", 0}};
  const double mean = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
  double var = 0.0;
  for (double x : v) var += (x - mean) * (x - mean);
  std::sort(v.begin(), v.end());
  return {{"mean", mean}, {"std", std::sqrt(var / v.size())}, {"median", v[v.size() / 2]}, {"n", v.size()}};
}

// Cost of the best solution published by `limit_s` (nullopt when none by then).
std::optional<double> cost_by(const FootstepPlan& plan, double limit_s) {
  std::optional<double> best;
  for (const auto& it : plan.iterations)
    if (it.time_s <= limit_s) best = it.cost;
  return best;
}

// The optimal reference costs of a previous run (its per_problem rows, or --log lines), by
// (map, problem), with the start and goal each row was generated with.
struct StoredOptimal {
  double cost_s = 0.0;
  Pose2 start, goal;
};
std::map<std::pair<int, int>, StoredOptimal> read_optimal_costs(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw Error("cannot read --optimal-from file " + file);
  std::vector<nlohmann::json> rows;
  try {
    if (file.size() >= 6 && file.substr(file.size() - 6) == ".jsonl") {
      for (std::string line; std::getline(in, line);)
        if (!line.empty()) rows.push_back(nlohmann::json::parse(line));
    } else {
      const auto j = nlohmann::json::parse(in);
      if (!j.contains("per_problem") || !j["per_problem"].is_array())
        throw Error("--optimal-from " + file + ": no per_problem array");
      for (const auto& r : j["per_problem"]) rows.push_back(r);
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error("--optimal-from " + file + ": " + e.what());
  }
  std::map<std::pair<int, int>, StoredOptimal> out;
  for (const auto& r : rows) {
    try {
      const auto& o = r.at("optimal");
      if (o.at("outcome") != "SUCCESS" || o.at("final_epsilon").get<double>() != 1.0 || o.at("cost_s").is_null())
        continue;  // no proven optimum stored: searched again
      const auto& s = r.at("start");
      const auto& g = r.at("goal");
      out[{r.at("map").get<int>(), r.at("problem").get<int>()}] = {
          o.at("cost_s").get<double>(), Pose2{s.at(0).get<double>(), s.at(1).get<double>(), s.at(2).get<double>()},
          Pose2{g.at(0).get<double>(), g.at(1).get<double>(), g.at(2).get<double>()}};
    } catch (const nlohmann::json::exception& e) {
      throw Error("--optimal-from " + file + ": malformed row: " + e.what());
    }
  }
  return out;
}

bool same_pose(const Pose2& a, const Pose2& b) {
  return std::abs(a.x - b.x) <= 1e-9 && std::abs(a.y - b.y) <= 1e-9 && std::abs(a.theta - b.theta) <= 1e-9;
}

// One Table I problem and everything measured on it (filled by one worker thread).
struct BenchProblem {
  int map = 0, index = 0;
  PlanningProblem problem;
  FootstepPlan optimal;
  std::map<std::string, FootstepPlan> plans;  // by heuristic
  FootstepPlan planar;
  bool optimal_stored = false;  // the optimal cost came from --optimal-from
};

nlohmann::json plan_json(const FootstepPlan& p) {
  nlohmann::json its = nlohmann::json::array();
  for (const auto& it : p.iterations) its.push_back({it.epsilon, it.cost, it.time_s, it.expansions});
  return {{"outcome", outcome_name(p.result.outcome)},
          {"cost_s", p.result.ok() ? nlohmann::json(p.cost_s) : nlohmann::json(nullptr)},
          {"final_epsilon", p.final_epsilon},
          {"expansions", p.expansions},
          {"time_s", p.time_s},
          {"setup_s", p.setup_s},
          {"iterations_eps_cost_time_expansions", its}};
}

// Table row name, e.g. dijkstra_5s (dijkstra_0.5s for fractional limits).
std::string row_name(const std::string& heuristic, double limit_s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%gs", limit_s);
  return heuristic + "_" + buf;
}

nlohmann::json problem_json(const BenchProblem& w) {
  nlohmann::json row = {{"map", w.map},
                        {"problem", w.index},
                        {"start", {w.problem.start.x, w.problem.start.y, w.problem.start.theta}},
                        {"goal", {w.problem.goal.x, w.problem.goal.y, w.problem.goal.theta}},
                        {"optimal", plan_json(w.optimal)}};
  if (w.optimal_stored) row["optimal"]["from_file"] = true;
  if (!w.planar.iterations.empty() || !w.planar.result.ok()) row["planar_only"] = plan_json(w.planar);
  for (const auto& [h, plan] : w.plans) row[h] = plan_json(plan);
  return row;
}

void check_bench_args(const FootstepBenchOptions& a) {
  require(a.maps >= 1 && a.problems >= 1, "--maps/--problems", ">= 1");
  require(a.jobs >= 1 && a.jobs <= 64, "--jobs", "in [1, 64]");
  require(a.clock == "thread_cpu" || a.clock == "wall", "--clock", "thread_cpu or wall");
  require(a.short_limit_s > 0.0 && a.long_limit_s >= a.short_limit_s, "--short-limit/--long-limit",
          "0 < short <= long");
}

// The seeded maps (appended to `maps`) and the problems on them that --only-map/--only-problem keep.
std::vector<BenchProblem> generate_problems(const FootstepBenchOptions& a, const TerrainGeneratorParams& tg,
                                            const FootstepPlanner& probe, std::vector<mapping::Heightmap>& maps) {
  const int per_map = std::max(1, a.problems / a.maps);
  std::vector<BenchProblem> work;
  for (int m = 0; m < a.maps; ++m) {
    maps.push_back(random_terrain(tg, 1000 + m));
    int i = 0;
    for (const auto& prob : random_problems(maps.back(), probe, per_map, 1.5, 3.0, 2000 + m)) {
      if ((a.only_map < 0 || a.only_map == m) && (a.only_problem < 0 || a.only_problem == i))
        work.push_back({m, i, prob, {}, {}, {}, false});
      ++i;
    }
  }
  // Problem 0 of every map first, then problem 1...: a partial run (--log) covers every map.
  std::stable_sort(work.begin(), work.end(), [](const BenchProblem& x, const BenchProblem& y) {
    return std::pair{x.index, x.map} < std::pair{y.index, y.map};
  });
  return work;
}

// Optimal costs do not depend on the heuristic: a previous run's may be reused, for the
// same problems only (the start and goal generated here must match the stored row's).
// Returns how many problems took theirs from --optimal-from.
int reuse_optimal_costs(const FootstepBenchOptions& a, std::vector<BenchProblem>& work) {
  std::map<std::pair<int, int>, StoredOptimal> stored;
  if (!a.optimal_from.empty()) stored = read_optimal_costs(a.optimal_from);
  int reused = 0;
  for (BenchProblem& w : work) {
    const auto it = stored.find({w.map, w.index});
    if (it == stored.end()) continue;
    if (!same_pose(it->second.start, w.problem.start) || !same_pose(it->second.goal, w.problem.goal))
      throw Error("--optimal-from: map " + std::to_string(w.map) + " problem " + std::to_string(w.index) +
                  " has another start/goal than the stored row (different problem generator or seeds)");
    w.optimal.result = {Outcome::SUCCESS, "optimal cost from " + a.optimal_from};
    w.optimal.cost_s = it->second.cost_s;
    w.optimal.final_epsilon = 1.0;
    w.optimal_stored = true;
    ++reused;
  }
  return reused;
}

// The names of --heuristics, each once, in their order.
std::vector<std::string> parse_heuristics(const std::string& list) {
  std::vector<std::string> heuristics;
  for (std::size_t b = 0; b <= list.size();) {
    const std::size_t e = std::min(list.find(',', b), list.size());
    const std::string h = list.substr(b, e - b);
    require(h == "dijkstra" || h == "euclidean", "--heuristics", "a comma-separated list of dijkstra, euclidean");
    if (std::find(heuristics.begin(), heuristics.end(), h) == heuristics.end()) heuristics.push_back(h);
    b = e + 1;
  }
  return heuristics;
}

using HeuristicPlanners = std::map<std::string, std::unique_ptr<FootstepPlanner>>;

// One ARA* planner per heuristic of --heuristics, searching up to the longer time limit.
HeuristicPlanners heuristic_planners(const FootstepBenchOptions& a, const FootstepPlannerParams& base) {
  HeuristicPlanners planners;
  for (const std::string& h : parse_heuristics(a.heuristics)) {
    FootstepPlannerParams p = base;
    p.heuristic = h;
    p.search.time_limit_s = a.long_limit_s;
    planners[h] = std::make_unique<FootstepPlanner>(p);
  }
  return planners;
}

using LogFile = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

// Each finished problem as one JSON line, for partial figures of a long run.
LogFile open_problem_log(const std::string& file) {
  LogFile log(nullptr, &std::fclose);
  if (!file.empty()) {
    log.reset(std::fopen(file.c_str(), "w"));
    if (!log) throw Error("cannot write --log file " + file);
  }
  return log;
}

// The planners every problem is searched with (`probe` places the start stance).
struct BenchPlanners {
  const FootstepPlanner& probe;
  const FootstepPlanner& optimal;
  const HeuristicPlanners& by_heuristic;
  const FootstepPlanner& planar;
};

// Everything measured on one problem: the optimal reference (unless stored), each heuristic's
// search and the planar-only baseline (unless skipped).
void search_problem(BenchProblem& w, const mapping::Heightmap& map, const BenchPlanners& p, bool skip_planar) {
  const Footstep start = p.probe.stance_for_body(w.problem.start, Foot::kLeft);
  if (!w.optimal_stored) w.optimal = p.optimal.plan(map, start, w.problem.goal);
  for (auto& [h, planner] : p.by_heuristic) w.plans[h] = planner->plan(map, start, w.problem.goal);
  if (!skip_planar) w.planar = p.planar.plan(map, start, w.problem.goal);
}

// Searches every problem, --jobs of them at a time, each on one thread; writes each finished
// problem to `log` (when not null).
void search_problems(const FootstepBenchOptions& a, const std::vector<mapping::Heightmap>& maps,
                     const BenchPlanners& planners, std::FILE* log, std::vector<BenchProblem>& work) {
  ProgressBar bar("footstep problems", work.size(), true);
  std::mutex bar_mutex;
  std::atomic<std::size_t> next{0}, done{0};
  auto worker = [&] {
    for (std::size_t k = next++; k < work.size(); k = next++) {
      BenchProblem& w = work[k];
      search_problem(w, maps[static_cast<std::size_t>(w.map)], planners, a.skip_planar);
      const std::lock_guard lock(bar_mutex);
      if (log) {
        std::fprintf(log, "%s\n", problem_json(w).dump().c_str());
        std::fflush(log);
      }
      bar.update(++done);
    }
  };
  std::vector<std::thread> threads;
  for (int j = 1; j < a.jobs; ++j) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
  bar.finish();
}

// One row of the table (a heuristic at a time limit): what the problems solved by then measured.
struct TableCell {
  std::vector<double> subopt, t_init, t_init_setup;
  int solved = 0;
};

// The table's cells and the counts over every problem (in problem order), with each problem's row.
struct BenchTally {
  std::map<std::string, TableCell> table;
  int planar_solved = 0, optimal_known = 0;
  int total = 0;
  nlohmann::json detail = nlohmann::json::array();
};

BenchTally tally_problems(const FootstepBenchOptions& a, const std::vector<BenchProblem>& work) {
  BenchTally t;
  t.total = static_cast<int>(work.size());
  for (const BenchProblem& w : work) {
    const bool have_opt = w.optimal.result.ok() && w.optimal.final_epsilon == 1.0;
    t.optimal_known += have_opt;
    t.planar_solved += w.planar.result.ok();
    nlohmann::json row = problem_json(w);
    for (const auto& [h, plan] : w.plans) {
      for (double limit : {a.short_limit_s, a.long_limit_s}) {
        TableCell& cell = t.table[row_name(h, limit)];
        const auto c = cost_by(plan, limit);
        if (!c) continue;
        ++cell.solved;
        cell.t_init.push_back(plan.first_solution_s);
        cell.t_init_setup.push_back(plan.setup_s + plan.first_solution_s);
        if (have_opt) cell.subopt.push_back(*c / w.optimal.cost_s);
      }
    }
    t.detail.push_back(row);
  }
  return t;
}

// The table's rows by name: each cell's statistics and solve rate.
nlohmann::json table_rows(const std::map<std::string, TableCell>& table, int total) {
  nlohmann::json rows = nlohmann::json::object();
  for (auto& [name, cell] : table) {
    std::vector<double> init_ms, init_setup_ms;
    for (double t : cell.t_init) init_ms.push_back(1000.0 * t);
    for (double t : cell.t_init_setup) init_setup_ms.push_back(1000.0 * t);
    rows[name] = {{"suboptimality_ratio", stats(cell.subopt)},
                  {"t_init_sol_ms", stats(init_ms)},
                  {"t_init_sol_with_setup_ms", stats(init_setup_ms)},
                  {"solve_rate_ratio", total ? static_cast<double>(cell.solved) / total : 0.0}};
  }
  return rows;
}

// What the goals of the reference are checked on: Dijkstra's mean suboptimality at the shorter
// limit (1e9 without one), the lowest solve rate and the highest median time to a first solution.
struct GoalMeasures {
  double subopt5 = 1e9, worst_rate = 1.0, worst_median_ms = 0.0;
};

GoalMeasures goal_measures(const nlohmann::json& rows, double short_limit_s) {
  GoalMeasures g;
  const std::string d5_name = row_name("dijkstra", short_limit_s);
  const nlohmann::json d5_mean =
      rows.contains(d5_name) ? rows[d5_name]["suboptimality_ratio"]["mean"] : nlohmann::json(nullptr);
  g.subopt5 = d5_mean.is_null() ? 1e9 : d5_mean.get<double>();
  for (auto& [k, v] : rows.items()) {
    g.worst_rate = std::min(g.worst_rate, v["solve_rate_ratio"].get<double>());
    if (!v["t_init_sol_ms"]["median"].is_null())
      g.worst_median_ms = std::max(g.worst_median_ms, v["t_init_sol_ms"]["median"].get<double>());
  }
  return g;
}

// The bench's result: its settings, the table, the goals and whether they are met, every problem.
nlohmann::json bench_json(const FootstepBenchOptions& a, const TerrainGeneratorParams& tg, SearchClockKind clock,
                          const Stopwatch& wall, int reused, const BenchTally& t) {
  const nlohmann::json rows = table_rows(t.table, t.total);
  const GoalMeasures g = goal_measures(rows, a.short_limit_s);
  return {{"problems", t.total},
          {"maps", a.maps},
          {"map_size_m", tg.size_m},
          {"map_resolution_m", tg.resolution_m},
          {"clock", search_clock_name(clock)},
          {"jobs", a.jobs},
          {"time_limits_s", {a.short_limit_s, a.long_limit_s}},
          {"optimal_limit_s", a.optimal_limit_s},
          {"bench_wall_s", wall.elapsed_ms() / 1000.0},
          {"optimal_solutions", t.optimal_known},
          {"optimal_costs_from_file", reused},
          {"optimal_from", a.optimal_from.empty() ? nlohmann::json(nullptr) : nlohmann::json(a.optimal_from)},
          {"table", rows},
          {"planar_only_solve_rate_ratio",
           a.skip_planar ? nlohmann::json(nullptr)
                         : nlohmann::json(t.total ? static_cast<double>(t.planar_solved) / t.total : 0.0)},
          {"goal_solve_rate_ratio", 1.0},
          {"goal_t_init_sol_median_ms", 100.0},
          {"goal_dijkstra_5s_suboptimality_ratio", 1.04},
          {"meets_goal_solve_rate", g.worst_rate >= 1.0},
          {"meets_goal_t_init_sol_median", g.worst_median_ms <= 100.0},
          {"meets_goal_suboptimality", g.subopt5 <= 1.04},
          {"per_problem", t.detail}};
}

}  // namespace

nlohmann::json run_footstep_bench(const FootstepBenchOptions& a) {
  check_bench_args(a);
  const SearchClockKind clock = a.clock == "wall" ? SearchClockKind::kWall : SearchClockKind::kThreadCpu;
  TerrainGeneratorParams tg;
  FootstepPlannerParams base;
  base.search.clock = clock;
  // The maps and problems first (seeded), then the searches, each problem on one thread: the
  // table is aggregated in problem order, so it does not depend on --jobs (with a CPU-time
  // clock, only the instant a time limit strikes varies from run to run).
  std::vector<mapping::Heightmap> maps;
  const FootstepPlanner probe(base);
  std::vector<BenchProblem> work = generate_problems(a, tg, probe, maps);
  FootstepPlannerParams opt = base;
  opt.search.initial_epsilon = 1.0;
  opt.search.time_limit_s = a.optimal_limit_s;
  const FootstepPlanner optimal_planner(opt);
  const int reused = reuse_optimal_costs(a, work);
  const HeuristicPlanners planners = heuristic_planners(a, base);
  FootstepPlannerParams planar = base;
  planar.planar_only = true;
  planar.search.time_limit_s = a.long_limit_s;
  const FootstepPlanner planar_planner(planar);
  const LogFile log = open_problem_log(a.log);
  const Stopwatch wall;
  search_problems(a, maps, {probe, optimal_planner, planners, planar_planner}, log.get(), work);
  return bench_json(a, tg, clock, wall, reused, tally_problems(a, work));
}

}  // namespace bipednav::bench
