// `bipednav plan grid|movingai` and `bipednav bench global` (the harness is bench/global; the Moving AI
// rows and their figures are bench/movingai_runner's).
#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_inflation.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_output.hpp"
#include "apps/cli_pose.hpp"
#include "apps/commands.hpp"
#include "bench/global.hpp"
#include "bench/movingai_runner.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/io/movingai.hpp"
#include "bipednav/mapping/global_costmap.hpp"
#include "bipednav/mapping/map_io.hpp"
#include "bipednav/planning/global/global_planner.hpp"
#include "bipednav/planning/global/global_planner_factory.hpp"
#include "bipednav/viz/canvas.hpp"
#include "bipednav/viz/figure_legend.hpp"

namespace bipednav::app {

namespace {

using nlohmann::json;

json pose_json(const Pose2& p) { return {{"x_m", p.x}, {"y_m", p.y}, {"yaw_rad", p.theta}}; }

struct GridOptions {
  std::string map, start, goal, planner = "dstar_lite", out;
  InflationFlags inflation{0.25, 0.8, 3.0, "unknown"};
  double cost_weight = 3.0;
  bool unknown_is_obstacle = false, json_out = false;
};

void write_plan_png(const std::string& file, const mapping::Costmap2D& map, const planning::global::PlanResult& r,
                    const Pose2& start, const Pose2& goal, const std::string& planner) {
  using viz::LegendMark;
  const viz::CostColors palette;
  const std::vector<viz::LegendEntry> legend = {{"obstacle", palette.lethal, LegendMark::kBox},
                                                {"inscribed / inflated", palette.inscribed, LegendMark::kBox},
                                                {"unknown", palette.unknown, LegendMark::kBox},
                                                {"path (" + planner + ")", viz::colors::kRed, LegendMark::kLine},
                                                {"start", viz::colors::kGrey, LegendMark::kArrow},
                                                {"goal", viz::colors::kOrange, LegendMark::kArrow}};
  const auto& g = map.geometry();
  viz::CanvasParams cp;
  cp.min_x_m = g.origin_x_m;
  cp.min_y_m = g.origin_y_m;
  cp.max_x_m = g.origin_x_m + g.size_x_m();
  cp.max_y_m = g.origin_y_m + g.size_y_m();
  cp.pixels_per_m = std::clamp(1200.0 / std::max(g.size_x_m(), g.size_y_m()), 2.0, 200.0);
  viz::Canvas canvas(viz::with_legend_bands(cp, legend));
  canvas.grid(map, palette);
  std::vector<Eigen::Vector2d> pts;
  for (const auto& p : r.path.poses) pts.push_back(p.position());
  if (pts.size() >= 2) canvas.polyline(pts, viz::colors::kRed, 2.0);
  const double arrow_m = 0.05 * std::max(g.size_x_m(), g.size_y_m());
  canvas.arrow(start, arrow_m, viz::colors::kGrey, 3.0);
  canvas.arrow(goal, arrow_m, viz::colors::kOrange, 3.0);
  viz::draw_title_and_legend(canvas, std::string(outcome_name(r.result.outcome)) + ": " + r.result.message, legend);
  canvas.write_png(file);
}

// Returns whether a path was found (the exit status).
bool run_grid(const GridOptions& o) {
  const Pose2 start = parse_pose(o.start, "--start"), goal = parse_pose(o.goal, "--goal");
  if (!o.out.empty()) prepare_output_file(o.out, "--out");
  const mapping::Costmap2D prior = mapping::read_map_server(o.map);
  mapping::GlobalCostmap costmap(prior.geometry(), o.inflation.params(prior.resolution_m()));
  costmap.set_occupancy(prior);
  planning::global::GlobalPlannerParams pp;
  pp.cost.cost_weight = o.cost_weight;
  pp.cost.unknown_is_obstacle = o.unknown_is_obstacle;
  auto planner = planning::global::make_global_planner(o.planner, pp);
  const planning::global::PlanResult r = planner->plan(costmap.costmap(), start, goal, {});
  if (!o.out.empty()) write_plan_png(o.out, costmap.costmap(), r, start, goal, o.planner);
  json poses = json::array();
  for (const auto& p : r.path.poses) poses.push_back(pose_json(p));
  json j = {{"planner", o.planner},
            {"outcome", outcome_name(r.result.outcome)},
            {"code", code(r.result.outcome)},
            {"message", r.result.message},
            {"cost", r.cost},
            {"length_m", r.path.length_m()},
            {"poses", r.path.size()},
            {"expansions", r.expansions},
            {"time_ms", r.time_ms},
            {"path", poses}};
  if (!o.out.empty()) j["png"] = o.out;
  print_figures(o.json_out, j, [&] {
    std::printf("%s (%s): %s\n  cost %.3f, length %.3f m, %zu poses, %zu expansions, %.3f ms\n",
                std::string(outcome_name(r.result.outcome)).c_str(), o.planner.c_str(), r.result.message.c_str(),
                r.cost, r.path.length_m(), r.path.size(), r.expansions, r.time_ms);
  });
  return r.result.ok();
}

// Returns whether every row was solved (the exit status).
bool run_movingai(const std::string& map_file, const std::string& scen_file, const std::string& planner_name,
                  bool json_out) {
  const auto map = io::read_movingai_map(map_file);
  const auto problems = io::read_movingai_scen(scen_file);
  auto planner = planning::global::make_global_planner(planner_name, {});
  const auto rows = bench::run_movingai(map, problems, *planner);
  json j = bench::movingai_report(rows, planner_name);
  const auto& s = j["summary"];
  const bool all_solved = s["solved"].get<std::size_t>() == s["rows"].get<std::size_t>();
  print_figures(json_out, j, [&] {
    std::printf("%s on %s: %d/%d rows solved, max |length - optimal| = %.6f cells, total %.1f ms\n",
                planner_name.c_str(), map_file.c_str(), s["solved"].get<int>(), s["rows"].get<int>(),
                s["max_abs_error_cells"].get<double>(), s["total_time_ms"].get<double>());
  });
  return all_solved;
}

// Prints the figures; returns whether the benchmark met its goals (the exit status).
bool bench_global(const bench::GlobalBenchOptions& o) {
  const json j = bench::run_global_bench(o);
  print_json(j);
  return bench_goals_met(j);
}

}  // namespace

void add_plan_commands(CLI::App& app, CLI::App& bench) {
  CLI::App* plan = app.add_subcommand("plan", "Global path planning (D* Lite, A*)");
  plan->require_subcommand(1);

  auto g = std::make_shared<GridOptions>();
  CLI::App* grid = plan->add_subcommand("grid", "Plan on a map_server map (inflated like the global costmap)");
  grid->add_option("map", g->map, "map_server YAML")->required()->check(CLI::ExistingFile);
  grid->add_option("--start", g->start, "x,y[,yaw] in metres/radians")->required();
  grid->add_option("--goal", g->goal, "x,y[,yaw] in metres/radians")->required();
  grid->add_option("--planner", g->planner, "dstar_lite | astar")->check(CLI::IsMember({"dstar_lite", "astar"}));
  grid->add_option("--out", g->out, "PNG of the costmap and the path");
  g->inflation.add_to(grid);
  grid->add_option("--cost-weight", g->cost_weight, "w in 1 + w * cost / 252")
      ->capture_default_str()
      ->check(check::non_negative());
  grid->add_flag("--unknown-is-obstacle", g->unknown_is_obstacle, "unknown cells are impassable");
  add_json_flag(grid, g->json_out);
  grid->callback([g] { report_task(run_grid(*g)); });

  auto m = std::make_shared<GridOptions>();
  CLI::App* mai = plan->add_subcommand("movingai", "Plan every row of a Moving AI scenario (unit cell costs)");
  mai->add_option("map", m->map, "Moving AI .map")->required()->check(CLI::ExistingFile);
  mai->add_option("scen", m->start, "Moving AI .scen")->required()->check(CLI::ExistingFile);
  mai->add_option("--planner", m->planner, "dstar_lite | astar")->check(CLI::IsMember({"dstar_lite", "astar"}));
  add_json_flag(mai, m->json_out);
  mai->callback([m] { report_task(run_movingai(m->map, m->start, m->planner, m->json_out)); });

  auto bo = std::make_shared<bench::GlobalBenchOptions>();
  CLI::App* b = bench.add_subcommand("global", "D* Lite replanning vs A* (three rooms), Moving AI first plans");
  accept_json_flag(b);
  b->add_option("--movingai-dir", bo->movingai_dir, "directory with maps/ and scen/ (default: tests/data/movingai)");
  b->add_option("--max-replans", bo->max_replans, "replan limit")
      ->capture_default_str()
      ->check(check::integer_at_least(1));
  b->callback([bo] { report_task(bench_global(*bo)); });
}

}  // namespace bipednav::app
