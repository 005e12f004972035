// `bipednav local plan` and `bipednav bench local` (the harness is bench/local).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_output.hpp"
#include "apps/cli_pose.hpp"
#include "apps/commands.hpp"
#include "bench/local.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/mapping/global_costmap.hpp"
#include "bipednav/mapping/map_io.hpp"
#include "bipednav/planning/global/global_planner.hpp"
#include "bipednav/planning/global/global_planner_factory.hpp"
#include "bipednav/planning/local/local_planner.hpp"
#include "bipednav/planning/local/local_planner_factory.hpp"
#include "bipednav/runner/run_figure.hpp"
#include "bipednav/viz/canvas.hpp"
#include "bipednav/viz/figure_legend.hpp"

namespace bipednav::app {

namespace {

using planning::local::LocalPlanner;

// The rolling local window (size_m square centred on the robot) cut from a larger map; cells
// beyond the map are unknown.
mapping::Costmap2D local_window(const mapping::Costmap2D& map, const Pose2& robot, double size_m) {
  const double res = map.resolution_m();
  mapping::GridGeometry g;
  g.width = g.height = static_cast<int>(std::lround(size_m / res));
  g.resolution_m = res;
  const auto& mg = map.geometry();
  // Snap the window to the map's cells.
  g.origin_x_m = mg.origin_x_m + std::floor((robot.x - 0.5 * size_m - mg.origin_x_m) / res) * res;
  g.origin_y_m = mg.origin_y_m + std::floor((robot.y - 0.5 * size_m - mg.origin_y_m) / res) * res;
  mapping::Costmap2D w(g, mapping::kUnknown);
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const auto c = g.cell_center(x, y);
      if (const auto mc = mg.world_to_cell(c.x(), c.y())) w.set_cost(x, y, map.cost(*mc));
    }
  }
  return w;
}

struct PlanOptions {
  std::string map, start, goal, out, planner = "teb";
  int steps = 600;
  int threads = 1;
};

constexpr viz::Color kDrivenColor{0.0, 0.55, 0.6, 1.0};

// The map, the global plan (red), the driven path (teal), the last local trajectory (green), the
// start, the goal and the robot at the end, with a legend and a scale bar.
void draw_run(const std::string& out, const mapping::Costmap2D& map, const Path& plan, const Pose2& start,
              const Pose2& goal, const std::vector<Eigen::Vector2d>& driven, const Path& last_traj, const Pose2& robot,
              const std::string& planner, const std::string& title) {
  using viz::LegendMark;
  const std::vector<viz::LegendEntry> legend = {
      {"obstacle (map)", viz::colors::kBlack, LegendMark::kBox},
      {"global plan (D* Lite)", viz::colors::kRed, LegendMark::kLine},
      {"driven path", kDrivenColor, LegendMark::kLine},
      {"last local trajectory (" + runner::local_planner_label(planner) + ")", viz::colors::kGreen, LegendMark::kLine},
      {"start", viz::colors::kGrey, LegendMark::kArrow},
      {"goal", viz::colors::kRed, LegendMark::kRing},
      {"robot at the end", viz::colors::kBlack, LegendMark::kArrow}};
  viz::CanvasParams cp;
  const auto& g = map.geometry();
  cp.min_x_m = g.origin_x_m, cp.min_y_m = g.origin_y_m;
  cp.max_x_m = g.origin_x_m + g.size_x_m(), cp.max_y_m = g.origin_y_m + g.size_y_m();
  cp.pixels_per_m = std::clamp(800.0 / std::max(g.size_x_m(), g.size_y_m()), 5.0, 100.0);
  viz::Canvas canvas(viz::with_legend_bands(cp, legend));
  canvas.grid(map);
  std::vector<Eigen::Vector2d> local, global;
  for (const auto& q : last_traj.poses) local.push_back(q.position());
  for (const auto& q : plan.poses) global.push_back(q.position());
  canvas.polyline(global, viz::colors::kRed, 1.5);
  canvas.polyline(driven, kDrivenColor, 2.0);
  canvas.polyline(local, viz::colors::kGreen, 2.0);
  canvas.arrow(start, 0.4, viz::colors::kGrey, 2.5);
  canvas.circle(goal.position(), 0.15, viz::colors::kNone, viz::colors::kRed, 2.5);
  canvas.arrow(robot, 0.4, viz::colors::kBlack, 2.5);
  viz::draw_title_and_legend(canvas, title, legend);
  canvas.write_png(out);
}

// The global plan the local planner follows: D* Lite on the map inflated with the global
// costmap's defaults, as the navigation server would hand it over.
planning::global::PlanResult global_plan(const mapping::Costmap2D& map, const Pose2& start, const Pose2& goal) {
  mapping::GlobalCostmapParams cp;
  cp.resolution_m = map.resolution_m();
  mapping::GlobalCostmap costmap(map.geometry(), cp);
  costmap.set_occupancy(map);
  planning::global::PlanResult r =
      planning::global::make_global_planner("dstar_lite", {})->plan(costmap.costmap(), start, goal, {});
  if (!r.path.empty()) r.path.poses.back().theta = goal.theta;
  return r;
}

// Drives the robot with the local planner along the global plan; returns whether it reached the goal.
bool local_plan(const PlanOptions& o) {
  const Pose2 start = parse_pose(o.start, "--start"), goal = parse_pose(o.goal, "--goal");
  if (!o.out.empty()) prepare_output_file(o.out, "--out");
  const mapping::Costmap2D map = mapping::read_map_server(o.map);
  planning::local::LocalPlannerParams params;
  params.teb.homotopy.num_threads = o.threads;
  params.validate();
  std::unique_ptr<LocalPlanner> planner = planning::local::make_local_planner(o.planner, params, nullptr);
  const planning::global::PlanResult global = global_plan(map, start, goal);
  nlohmann::json j;
  j["planner"] = o.planner;
  j["global_plan"] = {{"outcome", std::string(outcome_name(global.result.outcome))},
                      {"message", global.result.message},
                      {"length_m", global.path.length_m()}};
  const double dt = params.teb.control_period_s;
  Pose2 p = start;
  Twist v;
  std::vector<Eigen::Vector2d> driven{p.position()};
  Path last_traj;
  bool reached = false;
  int step = 0;
  std::string outcome = std::string(outcome_name(global.result.outcome));
  for (; global.result.ok() && step < o.steps; ++step) {
    const auto r = planner->compute(p, v, global.path, local_window(map, p, 8.0), step * dt);
    last_traj = r.trajectory;
    outcome = std::string(outcome_name(r.result.outcome));
    if ((reached = r.goal_reached)) break;
    v = r.cmd;
    p = p * Pose2{v.linear_x * dt, 0.0, v.angular_z * dt};
    driven.push_back(p.position());
  }
  j["reached"] = reached;
  j["last_outcome"] = outcome;
  j["cycles"] = step;
  j["time_s"] = step * dt;
  j["final_pose"] = {{"x_m", p.x}, {"y_m", p.y}, {"yaw_rad", p.theta}};
  if (!o.out.empty()) {
    char title[200];
    std::snprintf(title, sizeof title, "local plan (%s): %s after %.1f s",
                  runner::local_planner_label(o.planner).c_str(), reached ? "goal reached" : outcome.c_str(),
                  step * dt);
    draw_run(o.out, map, global.path, start, goal, driven, last_traj, p, o.planner, title);
    j["out"] = o.out;
  }
  print_json(j);
  return reached;
}

// Prints the figures; returns whether the benchmark met its goals (the exit status).
bool bench_local(const bench::LocalBenchOptions& o) {
  const nlohmann::json j = bench::run_local_bench(o);
  print_json(j);
  return bench_goals_met(j);
}

}  // namespace

void add_local_commands(CLI::App& app, CLI::App& bench) {
  CLI::App* local = app.add_subcommand("local", "Local planning (TEB or the path tracker)");
  local->require_subcommand(1);
  auto o = std::make_shared<PlanOptions>();
  CLI::App* plan = local->add_subcommand("plan", "Drive a simulated robot from start to goal on a map_server map");
  plan->add_option("map", o->map, "map_server YAML")->required()->check(CLI::ExistingFile);
  plan->add_option("--start", o->start, "start pose x,y[,yaw]")->required();
  plan->add_option("--goal", o->goal, "goal pose x,y[,yaw]")->required();
  plan->add_option("--out", o->out, "PNG of the map, the global plan, the driven path and the last local trajectory");
  plan->add_option("--planner", o->planner, "teb | tracker")
      ->capture_default_str()
      ->check(CLI::IsMember({"teb", "tracker"}));
  plan->add_option("--steps", o->steps, "maximum control cycles")
      ->capture_default_str()
      ->check(check::integer_at_least(1));
  plan->add_option("--threads", o->threads, "threads for the homotopy candidates")
      ->capture_default_str()
      ->check(check::integer_in(1, 256));
  accept_json_flag(plan);
  plan->callback([o] { report_task(local_plan(*o)); });

  auto* b = bench.add_subcommand("local", "TEB local planner cycle time with 0, 20 and 100 obstacles");
  auto ba = std::make_shared<bench::LocalBenchOptions>();
  b->add_option("--cycles", ba->cycles, "control cycles per obstacle count")
      ->capture_default_str()
      ->check(check::integer_at_least(1));
  b->add_option("--threads", ba->threads, "threads for the homotopy candidates")
      ->capture_default_str()
      ->check(check::integer_in(1, 256));
  accept_json_flag(b);
  b->add_option("--params", ba->params,
                "Navigation parameters YAML: its TEB settings (server.local.teb) over --robot's defaults, as `run "
                "--params` (without it: TebParams' defaults)");
  b->add_option("--robot", ba->robot, "Robot profile whose defaults --params overlays");
  b->callback([ba] { report_task(bench_local(*ba)); });
}

}  // namespace bipednav::app
