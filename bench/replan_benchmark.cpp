#include "bench/replan_benchmark.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/cpu_time.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/planning/global/global_planner_factory.hpp"

namespace bipednav::bench {

using planning::global::make_global_planner;
using planning::global::PlanResult;

namespace {

void fill_box(mapping::Costmap2D& m, double x0, double y0, double x1, double y1) {
  const auto& g = m.geometry();
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const auto c = g.cell_center(x, y);
      if (c.x() >= x0 && c.x() <= x1 && c.y() >= y0 && c.y() <= y1) m.set_cost(x, y, mapping::kLethal);
    }
}

void fill_disc(mapping::Costmap2D& m, double cx, double cy, double r) {
  const auto& g = m.geometry();
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x)
      if ((g.cell_center(x, y) - Eigen::Vector2d(cx, cy)).norm() <= r) m.set_cost(x, y, mapping::kLethal);
}

// Copies true obstacles within `radius_m` of the robot into the known obstacle grid; true when
// anything new was seen.
bool reveal(const mapping::Costmap2D& truth, mapping::Costmap2D& known, const Pose2& robot, double radius_m) {
  const auto& g = truth.geometry();
  const int r = static_cast<int>(std::ceil(radius_m / g.resolution_m));
  const auto rc = g.world_to_cell_unbounded(robot.x, robot.y);
  bool any = false;
  for (int y = std::max(0, rc->y - r); y <= std::min(g.height - 1, rc->y + r); ++y)
    for (int x = std::max(0, rc->x - r); x <= std::min(g.width - 1, rc->x + r); ++x) {
      if (truth.cost(x, y) != mapping::kLethal || known.cost(x, y) == mapping::kLethal) continue;
      if ((g.cell_center(x, y) - robot.position()).norm() > radius_m) continue;
      known.set_cost(x, y, mapping::kLethal);
      any = true;
    }
  return any;
}

struct Totals {
  double d_exp = 0, a_exp = 0, d_ms = 0, a_ms = 0, d_cpu_ms = 0, a_cpu_ms = 0;
};

}  // namespace

void ReplanBenchParams::validate() const {
  require(resolution_m > 0.0 && resolution_m <= 1.0, "resolution_m", "a value in (0, 1] m");
  require(sensor_radius_m > 0.0, "sensor_radius_m", "a value > 0");
  require(step_m > 0.0, "step_m", "a value > 0");
  require(goal_tolerance_m > 0.0, "goal_tolerance_m", "a value > 0");
  require(max_replans > 0, "max_replans", "a value > 0");
  inflation.validate();
  planner.validate();
}

ThreeRoomsWorld make_three_rooms_world(double resolution_m) {
  mapping::GridGeometry g;
  g.resolution_m = resolution_m;
  g.width = static_cast<int>(std::lround(30.0 / resolution_m));
  g.height = static_cast<int>(std::lround(6.0 / resolution_m));
  ThreeRoomsWorld w;
  w.walls = mapping::Costmap2D(g, mapping::kFree);
  const double t = 0.2;  // wall thickness
  fill_box(w.walls, 0.0, 0.0, 30.0, t);
  fill_box(w.walls, 0.0, 6.0 - t, 30.0, 6.0);
  fill_box(w.walls, 0.0, 0.0, t, 6.0);
  fill_box(w.walls, 30.0 - t, 0.0, 30.0, 6.0);
  fill_box(w.walls, 10.0 - t / 2, 0.0, 10.0 + t / 2, 4.0);  // door 1 at y in (4.0, 5.8)
  fill_box(w.walls, 20.0 - t / 2, 2.0, 20.0 + t / 2, 6.0);  // door 2 at y in (0.2, 2.0)
  w.truth = w.walls;
  fill_box(w.truth, 5.0, 2.4, 6.0, 6.0);  // room 1: blocks the straight line to door 1
  fill_disc(w.truth, 3.0, 1.2, 0.3);
  fill_box(w.truth, 14.0, 0.0, 15.0, 3.6);  // room 2: forces the robot over the top
  fill_disc(w.truth, 17.5, 4.5, 0.4);
  fill_box(w.truth, 24.0, 0.0, 25.0, 4.0);  // room 3
  fill_disc(w.truth, 22.5, 1.2, 0.3);
  fill_disc(w.truth, 27.0, 4.8, 0.3);
  w.start = {1.5, 3.0, 0.0};
  w.goal = {28.5, 2.5, 0.0};
  return w;
}

Pose2 advance_along(const Path& path, double distance_m) {
  if (path.poses.size() < 2) return path.empty() ? Pose2{} : path.poses.back();
  double left = distance_m;
  for (std::size_t i = 1; i < path.poses.size(); ++i) {
    const Pose2& a = path.poses[i - 1];
    const Pose2& b = path.poses[i];
    const double seg = distance(a, b);
    const double heading = std::atan2(b.y - a.y, b.x - a.x);
    if (seg >= left && seg > 0.0) return {a.x + (b.x - a.x) * left / seg, a.y + (b.y - a.y) * left / seg, heading};
    left -= seg;
  }
  return path.poses.back();
}

ReplanStats run_replan_benchmark(const ReplanBenchParams& params) {
  params.validate();
  const ThreeRoomsWorld world = make_three_rooms_world(params.resolution_m);
  mapping::Costmap2D obstacles = world.walls, known;
  mapping::Inflator inflator(params.inflation, params.resolution_m);
  auto dstar = make_global_planner("dstar_lite", params.planner);
  auto astar = make_global_planner("astar", params.planner);

  Pose2 robot = world.start;
  reveal(world.truth, obstacles, robot, params.sensor_radius_m);
  inflator.inflate(obstacles, known);
  ReplanStats st;
  PlanResult rd = dstar->plan(known, robot, world.goal, {});
  const PlanResult ra = astar->plan(known, robot, world.goal, {});
  if (!rd.result.ok()) throw Error("replan benchmark: first plan failed: " + rd.result.message);
  st.first_dstar_ms = rd.time_ms;
  st.first_astar_ms = ra.time_ms;
  st.first_dstar_expansions = rd.expansions;
  st.first_astar_expansions = ra.expansions;

  Totals tot;
  while (st.replans < params.max_replans) {
    if (distance(robot, world.goal) <= params.goal_tolerance_m) {
      st.reached_goal = true;
      break;
    }
    const Pose2 next = advance_along(rd.path, params.step_m);
    st.travelled_m += distance(robot, next);
    robot = next;
    mapping::ChangeSet changes;
    if (reveal(world.truth, obstacles, robot, params.sensor_radius_m)) {
      const mapping::Costmap2D before = known;
      inflator.inflate(obstacles, known);
      changes = mapping::diff(before, known);
    }
    st.changed_cells += changes.size();
    const double t0 = thread_cpu_ms();
    rd = dstar->plan(known, robot, world.goal, changes);
    const double t1 = thread_cpu_ms();
    const PlanResult a = astar->plan(known, robot, world.goal, {});
    tot.a_cpu_ms += thread_cpu_ms() - t1;
    tot.d_cpu_ms += t1 - t0;
    ++st.replans;
    if (rd.result.outcome != a.result.outcome || std::abs(rd.cost - a.cost) > 1e-9 * std::max(1.0, a.cost))
      ++st.cost_mismatches;
    tot.d_exp += static_cast<double>(rd.expansions);
    tot.a_exp += static_cast<double>(a.expansions);
    tot.d_ms += rd.time_ms;
    tot.a_ms += a.time_ms;
    st.dstar_max_ms = std::max(st.dstar_max_ms, rd.time_ms);
    st.astar_max_ms = std::max(st.astar_max_ms, a.time_ms);
    if (!rd.result.ok()) break;
  }
  const double n = std::max(1, st.replans);
  st.dstar_mean_expansions = tot.d_exp / n;
  st.astar_mean_expansions = tot.a_exp / n;
  st.dstar_mean_ms = tot.d_ms / n;
  st.astar_mean_ms = tot.a_ms / n;
  st.expansions_ratio = tot.a_exp / std::max(tot.d_exp, 1.0);
  st.time_ratio = tot.a_ms / std::max(tot.d_ms, 1e-9);
  st.dstar_cpu_mean_ms = tot.d_cpu_ms / n;
  st.astar_cpu_mean_ms = tot.a_cpu_ms / n;
  st.cpu_time_ratio = tot.a_cpu_ms / std::max(tot.d_cpu_ms, 1e-9);
  return st;
}

}  // namespace bipednav::bench
