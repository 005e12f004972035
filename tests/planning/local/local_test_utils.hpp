#pragma once

#include <cmath>

#include "bench/local_scene.hpp"
#include "bipednav/common/path.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/mapping/costmap2d.hpp"

namespace bipednav::planning::local::test {

// An empty costmap of size_m x size_m centred on (cx, cy), 0.05 m cells.
inline mapping::Costmap2D empty_costmap(double cx, double cy, double size_m = 8.0, double res = 0.05) {
  mapping::GridGeometry g;
  g.width = g.height = static_cast<int>(std::lround(size_m / res));
  g.resolution_m = res;
  g.origin_x_m = cx - 0.5 * size_m;
  g.origin_y_m = cy - 0.5 * size_m;
  return mapping::Costmap2D(g, mapping::kFree);
}

// Marks cells whose centre lies within r of (x, y) lethal, and those within r + inscribed inscribed.
inline void add_disc(mapping::Costmap2D& m, double x, double y, double r, double inscribed = 0.2) {
  bench::stamp_disc(m, x, y, r, inscribed);
}

// Axis-aligned lethal rectangle [x0, x1] x [y0, y1] with an inscribed ring.
inline void add_box(mapping::Costmap2D& m, double x0, double y0, double x1, double y1, double inscribed = 0.2) {
  const auto& g = m.geometry();
  for (int cy = 0; cy < g.height; ++cy) {
    for (int cx = 0; cx < g.width; ++cx) {
      const auto c = g.cell_center(cx, cy);
      const double dx = std::max({x0 - c.x(), 0.0, c.x() - x1}), dy = std::max({y0 - c.y(), 0.0, c.y() - y1});
      const double d = std::hypot(dx, dy);
      if (d <= 0.0)
        m.set_cost(cx, cy, mapping::kLethal);
      else if (d <= inscribed && m.cost(cx, cy) < mapping::kInscribed)
        m.set_cost(cx, cy, mapping::kInscribed);
    }
  }
}

// A straight plan from a to b with poses every step_m, facing along the line.
inline Path straight_plan(double ax, double ay, double bx, double by, double step_m = 0.1, double goal_yaw = NAN) {
  Path p;
  const double len = std::hypot(bx - ax, by - ay), th = std::atan2(by - ay, bx - ax);
  const int n = std::max(1, static_cast<int>(std::ceil(len / step_m)));
  for (int i = 0; i <= n; ++i) {
    const double f = static_cast<double>(i) / n;
    p.poses.push_back({ax + f * (bx - ax), ay + f * (by - ay), th});
  }
  if (std::isfinite(goal_yaw)) p.poses.back().theta = goal_yaw;
  return p;
}

// Integrates a unicycle over dt with the command (no lateral velocity).
inline Pose2 integrate(const Pose2& p, const Twist& cmd, double dt) {
  Pose2 q = p;
  const int sub = 10;
  for (int i = 0; i < sub; ++i) {
    const double h = dt / sub;
    q.x += cmd.linear_x * std::cos(q.theta) * h;
    q.y += cmd.linear_x * std::sin(q.theta) * h;
    q.theta = normalize_angle(q.theta + cmd.angular_z * h);
  }
  return q;
}

}  // namespace bipednav::planning::local::test

#include <functional>
#include <vector>

#include "bipednav/planning/local/local_planner.hpp"

namespace bipednav::planning::local::test {

// Closed loop: a unicycle integrating the planner's commands every period_s.
struct SimRun {
  Pose2 final_pose;
  bool reached = false;
  int steps = 0;
  std::vector<Twist> cmds;
  std::vector<Pose2> poses;
  std::vector<Outcome> outcomes;
};

inline SimRun simulate(LocalPlanner& planner, Pose2 start, const Path& plan, const mapping::Costmap2D& map,
                       int max_steps, double period_s = 0.1) {
  SimRun run;
  Pose2 p = start;
  Twist v;
  for (int i = 0; i < max_steps; ++i) {
    const auto r = planner.compute(p, v, plan, map, i * period_s);
    run.outcomes.push_back(r.result.outcome);
    run.cmds.push_back(r.cmd);
    run.steps = i + 1;
    if (r.goal_reached) {
      run.reached = true;
      break;
    }
    v = r.cmd;
    p = integrate(p, v, period_s);
    run.poses.push_back(p);
  }
  run.final_pose = p;
  return run;
}

}  // namespace bipednav::planning::local::test
