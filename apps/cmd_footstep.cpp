// `bipednav footsteps` (plan on a heightmap image and draw the plan) and `bench footsteps`
// (the second reference's Table I on random cluttered heightmaps).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <numeric>

#include "apps/cli_pose.hpp"
#include "apps/commands.hpp"
#include "bipednav/common/progress.hpp"
#include "bipednav/io/heightmap_image.hpp"
#include "bipednav/planning/footstep/footstep_planner.hpp"
#include "bipednav/planning/footstep/terrain_generator.hpp"
#include "bipednav/runner/footstep_drawing.hpp"
#include "bipednav/viz/canvas.hpp"

namespace bipednav::app {

namespace {

using namespace footstep;

// The heightmap with the planned feet on top (runner/footstep_drawing.hpp).
void draw_plan(const std::filesystem::path& file, const mapping::Heightmap& map, const FootstepPlanner& planner,
               const FootstepPlan& plan, const Pose2& goal) {
  viz::Canvas c(runner::canvas_for(map.geometry()));
  runner::draw_heightmap(c, map);
  runner::draw_footsteps(c, planner.lattice().actions().body, plan.steps, plan.actions);
  runner::draw_goal(c, goal);
  c.write_png(file);
}

struct FootstepArgs {
  std::string heightmap, start, goal, out = "footsteps.png", robot = "nao", heuristic = "dijkstra";
  double resolution_m = 0.02, min_height_m = -0.5, max_height_m = 1.0, time_limit_s = 5.0;
};

void footsteps_command(const FootstepArgs& a) {
  const mapping::Heightmap map =
      io::read_heightmap_image(a.heightmap, {a.resolution_m, a.min_height_m, a.max_height_m, 0.0, 0.0});
  FootstepPlannerParams p;
  p.robot = a.robot;
  p.heuristic = a.heuristic;
  p.search.time_limit_s = a.time_limit_s;
  const FootstepPlanner planner(p);
  const Pose2 start = parse_pose(a.start, "--start"), goal = parse_pose(a.goal, "--goal");
  const FootstepPlan plan = planner.plan(map, planner.stance_for_body(start, Foot::kLeft), goal);
  std::printf("%s: %s\n", std::string(outcome_name(plan.result.outcome)).c_str(), plan.result.message.c_str());
  if (plan.result.ok()) {
    std::printf("  %zu steps, %.2f s of walking, bound eps %.2f, first solution after %.3f s, %zu expansions\n",
                plan.actions.size(), plan.cost_s, plan.final_epsilon, plan.first_solution_s, plan.expansions);
  }
  draw_plan(a.out, map, planner, plan, goal);
  std::printf("  wrote %s\n", a.out.c_str());
  if (!plan.result.ok()) throw Error("no footstep plan: " + plan.result.message);
}

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

struct BenchArgs {
  int maps = 10, problems = 10;
  double long_limit_s = 10.0, short_limit_s = 5.0, optimal_limit_s = 120.0;
};

void bench_footsteps(const BenchArgs& a) {
  TerrainGeneratorParams tg;
  FootstepPlannerParams base;
  const int per_map = std::max(1, a.problems / a.maps);
  struct Cell {
    std::vector<double> subopt, t_init;
    int solved = 0;
  };
  std::map<std::string, Cell> table;
  int planar_solved = 0, total = 0, optimal_known = 0;
  ProgressBar bar("footstep problems", static_cast<std::size_t>(per_map * a.maps), true);
  for (int m = 0; m < a.maps; ++m) {
    const mapping::Heightmap map = random_terrain(tg, 1000 + m);
    const FootstepPlanner probe(base);
    for (const auto& prob : random_problems(map, probe, per_map, 1.5, 3.0, 2000 + m)) {
      ++total;
      const Footstep start = probe.stance_for_body(prob.start, Foot::kLeft);
      FootstepPlannerParams opt = base;
      opt.search.initial_epsilon = 1.0;
      opt.search.time_limit_s = a.optimal_limit_s;
      const FootstepPlan best = FootstepPlanner(opt).plan(map, start, prob.goal);
      const bool have_opt = best.result.ok() && best.final_epsilon == 1.0;
      optimal_known += have_opt;
      for (const std::string h : {"dijkstra", "euclidean"}) {
        FootstepPlannerParams p = base;
        p.heuristic = h;
        p.search.time_limit_s = a.long_limit_s;
        const FootstepPlan plan = FootstepPlanner(p).plan(map, start, prob.goal);
        for (double limit : {a.short_limit_s, a.long_limit_s}) {
          Cell& cell = table[h + "_" + std::to_string(static_cast<int>(limit)) + "s"];
          const auto c = cost_by(plan, limit);
          if (!c) continue;
          ++cell.solved;
          cell.t_init.push_back(plan.first_solution_s);
          if (have_opt) cell.subopt.push_back(*c / best.cost_s);
        }
      }
      FootstepPlannerParams planar = base;
      planar.planar_only = true;
      planar.search.time_limit_s = a.long_limit_s;
      planar_solved += FootstepPlanner(planar).plan(map, start, prob.goal).result.ok();
      bar.update(static_cast<std::size_t>(total));
    }
  }
  bar.finish();
  nlohmann::json rows = nlohmann::json::object();
  for (auto& [name, cell] : table) {
    std::vector<double> init_ms;
    for (double t : cell.t_init) init_ms.push_back(1000.0 * t);
    rows[name] = {{"suboptimality_ratio", stats(cell.subopt)},
                  {"t_init_sol_ms", stats(init_ms)},
                  {"solve_rate_ratio", total ? static_cast<double>(cell.solved) / total : 0.0}};
  }
  const auto& d5 = rows["dijkstra_" + std::to_string(static_cast<int>(a.short_limit_s)) + "s"];
  const double subopt5 =
      d5["suboptimality_ratio"]["mean"].is_null() ? 1e9 : d5["suboptimality_ratio"]["mean"].get<double>();
  double worst_rate = 1.0, worst_median_ms = 0.0;
  for (auto& [k, v] : rows.items()) {
    worst_rate = std::min(worst_rate, v["solve_rate_ratio"].get<double>());
    if (!v["t_init_sol_ms"]["median"].is_null())
      worst_median_ms = std::max(worst_median_ms, v["t_init_sol_ms"]["median"].get<double>());
  }
  nlohmann::json out = {{"problems", total},
                        {"maps", a.maps},
                        {"map_size_m", tg.size_m},
                        {"map_resolution_m", tg.resolution_m},
                        {"optimal_solutions", optimal_known},
                        {"table", rows},
                        {"planar_only_solve_rate_ratio", total ? static_cast<double>(planar_solved) / total : 0.0},
                        {"goal_solve_rate_ratio", 1.0},
                        {"goal_t_init_sol_median_ms", 100.0},
                        {"goal_dijkstra_5s_suboptimality_ratio", 1.04},
                        {"meets_goal_solve_rate", worst_rate >= 1.0},
                        {"meets_goal_t_init_sol_median", worst_median_ms <= 100.0},
                        {"meets_goal_suboptimality", subopt5 <= 1.04}};
  std::printf("%s\n", out.dump(2).c_str());
}

}  // namespace

void add_footstep_commands(CLI::App& app, CLI::App& bench) {
  auto a = std::make_shared<FootstepArgs>();
  CLI::App* fs = app.add_subcommand("footsteps", "Plan footsteps on a heightmap image and draw them");
  fs->add_option("heightmap", a->heightmap, "Heightmap PNG, or a YAML with image/resolution_m/min/max_height_m")
      ->required();
  fs->add_option("--start", a->start, "Start body pose x,y[,yaw]")->required();
  fs->add_option("--goal", a->goal, "Goal body pose x,y[,yaw]")->required();
  fs->add_option("--out", a->out, "Output PNG")->capture_default_str();
  fs->add_option("--robot", a->robot, "nao or digit")->capture_default_str();
  fs->add_option("--heuristic", a->heuristic, "dijkstra or euclidean")->capture_default_str();
  fs->add_option("--resolution", a->resolution_m, "PNG: metres per pixel")->capture_default_str();
  fs->add_option("--min-height", a->min_height_m, "PNG: height of grey 0")->capture_default_str();
  fs->add_option("--max-height", a->max_height_m, "PNG: height of grey 255")->capture_default_str();
  fs->add_option("--time-limit", a->time_limit_s, "ARA* time limit, s")->capture_default_str();
  fs->callback([a] { footsteps_command(*a); });

  auto b = std::make_shared<BenchArgs>();
  auto json = std::make_shared<bool>(true);
  CLI::App* bf = bench.add_subcommand("footsteps", "Table I of the footstep reference on random heightmaps");
  bf->add_option("--maps", b->maps, "Random 2.5 x 2.5 m heightmaps")->capture_default_str();
  bf->add_option("--problems", b->problems, "Start/goal pairs in all (the reference: 100)")->capture_default_str();
  bf->add_option("--optimal-limit", b->optimal_limit_s, "Time cap of the optimal reference search, s")
      ->capture_default_str();
  bf->add_flag("--json", *json, "Print one JSON object (the default)");
  bf->callback([b] { bench_footsteps(*b); });
}

}  // namespace bipednav::app
