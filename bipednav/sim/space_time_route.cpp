#include "bipednav/sim/space_time_route.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/footprint2d.hpp"

namespace bipednav::sim {

void SpaceTimeRouteParams::validate() const {
  require(std::isfinite(resolution_m) && resolution_m >= 0.005, "space_time_route.resolution_m", ">= 0.005 m");
  require(std::isfinite(margin_m) && margin_m >= 0.0, "space_time_route.margin_m", ">= 0");
  require(std::isfinite(sample_step_s) && sample_step_s > 0.0, "space_time_route.sample_step_s", "> 0");
  require(std::isfinite(height_m) && height_m > collision.ground_clearance_m, "space_time_route.height_m",
          "> collision.ground_clearance_m");
  collision.validate();
}

namespace {

struct Grid {
  Eigen::Vector2d min;
  double res = 0.05;
  long nx = 1, ny = 1;

  std::size_t size() const { return static_cast<std::size_t>(nx * ny); }
  Eigen::Vector2d center(long x, long y) const {
    return min + res * Eigen::Vector2d(static_cast<double>(x), static_cast<double>(y));
  }
  std::size_t index(long x, long y) const { return static_cast<std::size_t>(y * nx + x); }
  bool contains(long x, long y) const { return x >= 0 && y >= 0 && x < nx && y < ny; }
  // Calls f(x, y) for the cells whose centres lie in the box [lo, hi].
  template <class F>
  void for_cells_in(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, F&& f) const {
    const long x0 = std::max(0L, static_cast<long>(std::ceil((lo.x() - min.x()) / res)));
    const long y0 = std::max(0L, static_cast<long>(std::ceil((lo.y() - min.y()) / res)));
    const long x1 = std::min(nx - 1, static_cast<long>(std::floor((hi.x() - min.x()) / res)));
    const long y1 = std::min(ny - 1, static_cast<long>(std::floor((hi.y() - min.y()) / res)));
    for (long y = y0; y <= y1; ++y)
      for (long x = x0; x <= x1; ++x) f(x, y);
  }
};

// Marks the cells whose centres are closer than `reach` to the footprint.
void mark_near(const Grid& g, const Footprint2D& f, double reach, std::vector<std::uint8_t>& marks) {
  const Eigen::Vector2d pad = Eigen::Vector2d::Constant(reach);
  g.for_cells_in(f.bbox_min - pad, f.bbox_max + pad, [&](long x, long y) {
    std::uint8_t& m = marks[g.index(x, y)];
    if (m == 0 && signed_distance(f, g.center(x, y)) < reach) m = 1;
  });
}

// One step's moves: stay, the 8 neighbours, and two cells straight (through the cell between).
struct Move {
  long dx, dy;
  bool through_middle;
};
constexpr std::array<Move, 13> kMoves{{{0, 0, false},
                                       {1, 0, false},
                                       {-1, 0, false},
                                       {0, 1, false},
                                       {0, -1, false},
                                       {1, 1, false},
                                       {1, -1, false},
                                       {-1, 1, false},
                                       {-1, -1, false},
                                       {2, 0, true},
                                       {-2, 0, true},
                                       {0, 2, true},
                                       {0, -2, true}}};

// The cells some person comes within `reach` of during [t0, t0 + dt]: each person's footprints
// at samples at most sample_step_s apart, each widened by half the way the person moves to the
// next sample (what it can cover in between).
void mark_people(const Grid& g, const World& world, double t0, double dt, double reach, const SpaceTimeRouteParams& p,
                 std::vector<std::uint8_t>& marks) {
  std::fill(marks.begin(), marks.end(), 0);
  const int samples = std::max(1, static_cast<int>(std::ceil(dt / p.sample_step_s)));
  const double z_lo = p.collision.ground_clearance_m, z_hi = p.height_m;
  std::vector<SE3> poses(static_cast<std::size_t>(samples) + 1);
  for (const Actor& a : world.actors) {
    for (int j = 0; j <= samples; ++j) poses[static_cast<std::size_t>(j)] = a.pose_at(t0 + dt * j / samples);
    for (std::size_t j = 0; j < poses.size(); ++j) {
      const auto moved = [&](std::size_t n) {
        return (poses[n].translation() - poses[j].translation()).head<2>().norm();
      };
      const double half_move = 0.5 * std::max(j > 0 ? moved(j - 1) : 0.0, j + 1 < poses.size() ? moved(j + 1) : 0.0);
      for (const Geometry& part : a.parts)
        for (const Footprint2D& f : slab_footprints(part, poses[j], z_lo, z_hi))
          mark_near(g, f, reach + half_move, marks);
    }
  }
}

// The earliest step at which a goal cell is reachable, propagating `reach` (the reachable cells)
// through `steps` steps; with_people also masks each step's people. Returns -1 when never, and
// leaves in `reach` the cells reachable at the last step.
long propagate(const Grid& g, const World& world, const std::vector<std::uint8_t>& blocked,
               const std::vector<bool>& goal, double dt, long steps, double reach_m, bool with_people,
               bool stop_at_goal, const SpaceTimeRouteParams& p, std::vector<std::uint8_t>& reach) {
  long arrival = -1;
  for (std::size_t i = 0; i < reach.size() && arrival < 0; ++i)
    if (reach[i] && goal[i]) arrival = 0;
  if (arrival == 0 && stop_at_goal) return 0;
  std::vector<std::uint8_t> people(g.size(), 0), next(g.size(), 0);
  const auto open = [&](long x, long y) {
    if (!g.contains(x, y)) return false;
    const std::size_t i = g.index(x, y);
    return blocked[i] == 0 && people[i] == 0;
  };
  for (long k = 0; k < steps; ++k) {
    if (with_people) mark_people(g, world, static_cast<double>(k) * dt, dt, reach_m, p, people);
    std::fill(next.begin(), next.end(), 0);
    bool any = false, at_goal = false;
    for (long y = 0; y < g.ny; ++y) {
      for (long x = 0; x < g.nx; ++x) {
        if (!reach[g.index(x, y)] || !open(x, y)) continue;
        for (const Move& m : kMoves) {
          const long tx = x + m.dx, ty = y + m.dy;
          if (!open(tx, ty) || (m.through_middle && !open(x + m.dx / 2, y + m.dy / 2))) continue;
          const std::size_t i = g.index(tx, ty);
          next[i] = 1;
          any = true;
          at_goal = at_goal || goal[i];
        }
      }
    }
    reach.swap(next);
    if (!any) return arrival;
    if (arrival < 0 && at_goal) {
      arrival = k + 1;
      if (stop_at_goal) return arrival;
    }
  }
  return arrival;
}

}  // namespace

SpaceTimeRoute space_time_route(const World& world, const RouteArea& area, const Eigen::Vector2d& start,
                                const Eigen::Vector2d& goal, double goal_tolerance_m, double radius_m,
                                double max_speed_mps, double time_limit_s, const SpaceTimeRouteParams& params) {
  params.validate();
  require(area.min.allFinite() && area.max.allFinite() && (area.max.array() > area.min.array()).all(),
          "space_time_route.area", "finite, min < max");
  require(std::isfinite(radius_m) && radius_m > 0.0, "space_time_route.radius_m", "> 0");
  require(std::isfinite(max_speed_mps) && max_speed_mps > 0.0, "space_time_route.max_speed_mps", "> 0");
  require(std::isfinite(time_limit_s) && time_limit_s > 0.0, "space_time_route.time_limit_s", "> 0");
  require(std::isfinite(goal_tolerance_m) && goal_tolerance_m >= 0.0, "space_time_route.goal_tolerance_m", ">= 0");
  require(start.allFinite() && goal.allFinite(), "space_time_route.start/goal", "finite");

  Grid g{area.min, params.resolution_m};
  const double cells_x = std::floor((area.max.x() - area.min.x()) / g.res) + 1.0;
  const double cells_y = std::floor((area.max.y() - area.min.y()) / g.res) + 1.0;
  require(cells_x * cells_y <= 4e6, "space_time_route.resolution_m", "coarse enough for at most 4e6 cells in the area");
  g.nx = static_cast<long>(cells_x);
  g.ny = static_cast<long>(cells_y);

  SpaceTimeRoute out;
  out.cells = g.size();
  out.step_s = 2.0 * g.res / max_speed_mps;
  const double reach_m = radius_m + params.margin_m;

  std::vector<std::uint8_t> blocked(g.size(), 0);
  for (const Geometry& s : world.statics)
    for (const Footprint2D& f :
         slab_footprints(s, SE3::Identity(), params.collision.ground_clearance_m, params.height_m))
      mark_near(g, f, reach_m, blocked);
  std::vector<bool> at_goal(g.size(), false);
  const Eigen::Vector2d tol = Eigen::Vector2d::Constant(goal_tolerance_m);
  g.for_cells_in(goal - tol, goal + tol, [&](long x, long y) {
    if ((g.center(x, y) - goal).norm() <= goal_tolerance_m) at_goal[g.index(x, y)] = true;
  });

  const long sx = std::lround((start.x() - g.min.x()) / g.res), sy = std::lround((start.y() - g.min.y()) / g.res);
  if (!g.contains(sx, sy) || blocked[g.index(sx, sy)] != 0) return out;
  const long steps = static_cast<long>(std::floor(time_limit_s / out.step_s));
  std::vector<std::uint8_t> reach(g.size(), 0);
  reach[g.index(sx, sy)] = 1;
  const long static_arrival =
      propagate(g, world, blocked, at_goal, out.step_s, steps, reach_m, false, true, params, reach);
  if (static_arrival < 0) return out;
  out.static_arrival_s = static_cast<double>(static_arrival) * out.step_s;

  std::fill(reach.begin(), reach.end(), 0);
  reach[g.index(sx, sy)] = 1;
  const long arrival = propagate(g, world, blocked, at_goal, out.step_s, steps, reach_m, true, false, params, reach);
  if (arrival >= 0) out.arrival_s = static_cast<double>(arrival) * out.step_s;
  for (std::size_t i = 0; i < reach.size() && !out.reachable; ++i) out.reachable = reach[i] && at_goal[i];
  return out;
}

SpaceTimeRoute scenario_space_time_route(const Scenario& scenario, const RobotProfile& robot,
                                         SpaceTimeRouteParams params) {
  require(!scenario.goals.empty(), "scenario.goals", "at least one goal");
  params.height_m = robot.height_m;
  const Bounds& b = scenario.bounds;
  return space_time_route(scenario.world, RouteArea{{b.min_x_m, b.min_y_m}, {b.max_x_m, b.max_y_m}},
                          scenario.start.position(), scenario.goals.back().pose.position(), scenario.goal_tolerance_m,
                          needed_clearance_m(robot), robot.limits.max_vel_x_mps, scenario.time_limit_s, params);
}

}  // namespace bipednav::sim
