#include "bench/local_drive.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bipednav/mapping/global_costmap.hpp"
#include "bipednav/mapping/map_io.hpp"
#include "bipednav/planning/global/global_planner.hpp"
#include "bipednav/planning/global/global_planner_factory.hpp"
#include "bipednav/planning/local/local_planner.hpp"
#include "bipednav/planning/local/local_planner_factory.hpp"
#include "bipednav/runner/run_figure.hpp"
#include "bipednav/viz/canvas.hpp"
#include "bipednav/viz/figure_legend.hpp"

namespace bipednav::bench {

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

}  // namespace

nlohmann::json run_local_drive(const LocalDriveOptions& o) {
  const Pose2 &start = o.start, &goal = o.goal;
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
  return j;
}

}  // namespace bipednav::bench
