#include "bipednav/planning/global/global_planner.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "bipednav/common/error.hpp"

namespace bipednav::planning::global {

void GlobalPlannerParams::validate() const {
  cost.validate();
  require(std::isfinite(max_planning_time_ms) && max_planning_time_ms >= 0.0, "max_planning_time_ms",
          "a finite value >= 0 (0 = no limit)");
  require(std::isfinite(goal_tolerance_m) && goal_tolerance_m >= 0.0 && goal_tolerance_m <= 1.0, "goal_tolerance_m",
          "in [0, 1] m");
}

namespace {

std::string fmt(const char* f, double a, double b) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), f, a, b);
  return buf;
}

// A mapped cell closed only for its nearness to an obstacle (inscribed, or within the planning
// clearance), not for being one.
bool within_clearance_only(std::uint8_t cost, const GridCostParams& p) {
  return cost <= mapping::kInscribed && static_cast<int>(cost) >= p.min_impassable_cost;
}

std::string cell_str(const mapping::Cell& c) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), "(%d, %d)", c.x, c.y);
  return buf;
}

std::string cost_str(std::uint8_t c, const GridCostParams& p) {
  if (c == mapping::kLethal) return "254 (lethal)";
  if (c == mapping::kInscribed) return "253 (inscribed: the robot's centre may not stand there)";
  if (c == mapping::kUnknown) return "255 (unknown, and unknown cells are obstacles)";
  if (within_clearance_only(c, p)) return std::to_string(c) + " (within the planning clearance of an obstacle)";
  return std::to_string(c);
}

// The cell of a pose, or a PLAN_OUT_OF_MAP failure naming the map's extent.
std::optional<mapping::Cell> locate(const mapping::GridGeometry& g, const Pose2& p, const char* what, Result& failure) {
  if (!p.is_finite()) {
    failure = {Outcome::PLAN_OUT_OF_MAP, std::string(what) + " pose is not finite"};
    return std::nullopt;
  }
  auto c = g.world_to_cell(p.x, p.y);
  if (!c) {
    failure = {Outcome::PLAN_OUT_OF_MAP, std::string(what) + fmt(" (%.3f, %.3f) m", p.x, p.y) + " is outside the map" +
                                             fmt(" (x in [%.3f, %.3f) m", g.origin_x_m, g.origin_x_m + g.size_x_m()) +
                                             fmt(", y in [%.3f, %.3f) m)", g.origin_y_m, g.origin_y_m + g.size_y_m())};
  }
  return c;
}

}  // namespace

std::optional<mapping::Cell> goal_search_cell(const mapping::Costmap2D& map, const Pose2& goal,
                                              const GlobalPlannerParams& params) {
  const auto& g = map.geometry();
  if (!goal.is_finite() || map.data().size() != g.size()) return std::nullopt;
  const auto t = g.world_to_cell(goal.x, goal.y);
  if (!t) return std::nullopt;
  const std::uint8_t gc = map.cost(*t);
  if (std::isfinite(cell_factor(gc, params.cost))) return t;
  if (!within_clearance_only(gc, params.cost) || params.goal_tolerance_m <= 0.0) return std::nullopt;
  const int r = static_cast<int>(std::ceil(params.goal_tolerance_m / g.resolution_m)) + 1;
  const double tol2 = params.goal_tolerance_m * params.goal_tolerance_m;
  std::optional<mapping::Cell> best;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (int y = t->y - r; y <= t->y + r; ++y)
    for (int x = t->x - r; x <= t->x + r; ++x) {
      const mapping::Cell c{x, y};
      if (!g.in_bounds(c) || !std::isfinite(cell_factor(map.cost(c), params.cost))) continue;
      const Eigen::Vector2d p = g.cell_center(c);
      const double d2 = (p.x() - goal.x) * (p.x() - goal.x) + (p.y() - goal.y) * (p.y() - goal.y);
      if (d2 <= tol2 && d2 < best_d2) {
        best = c;
        best_d2 = d2;
      }
    }
  return best;
}

std::optional<Endpoints> resolve_endpoints(const mapping::Costmap2D& map, const Pose2& start, const Pose2& goal,
                                           const GlobalPlannerParams& params, Result& failure) {
  const auto& g = map.geometry();
  if (g.width <= 0 || g.height <= 0 || map.data().size() != g.size()) {
    failure = {Outcome::PLAN_OUT_OF_MAP, "the map is empty"};
    return std::nullopt;
  }
  const auto s = locate(g, start, "start", failure);
  if (!s) return std::nullopt;
  const auto t = locate(g, goal, "goal", failure);
  if (!t) return std::nullopt;
  const std::uint8_t sc = map.cost(*s), gc = map.cost(*t);
  const auto goal_cell = goal_search_cell(map, goal, params);
  if (!goal_cell) {
    std::string why = "goal cell " + cell_str(*t) + " has cost " + cost_str(gc, params.cost);
    if (within_clearance_only(gc, params.cost) && params.goal_tolerance_m > 0.0) {
      char buf[96];
      std::snprintf(buf, sizeof(buf), " and no traversable cell lies within goal_tolerance_m = %.3f m",
                    params.goal_tolerance_m);
      why += buf;
    }
    failure = {Outcome::BLOCKED_GOAL, why};
    return std::nullopt;
  }
  Endpoints e{g.index(*s), g.index(*goal_cell), false};
  if (!std::isfinite(cell_factor(sc, params.cost))) {
    if (sc == mapping::kLethal || !params.allow_start_in_inscribed) {
      failure = {Outcome::BLOCKED_START, "start cell " + cell_str(*s) + " has cost " + cost_str(sc, params.cost) +
                                             (sc == mapping::kLethal ? "" : " and allow_start_in_inscribed is false")};
      return std::nullopt;
    }
    e.start_exempt = true;
  }
  return e;
}

Path make_world_path(const mapping::GridGeometry& geometry, const std::vector<std::size_t>& cells, const Pose2& start,
                     const Pose2& goal) {
  Path path;
  path.poses.push_back(start);
  for (std::size_t i = 1; i + 1 < cells.size(); ++i) {
    const Eigen::Vector2d c = geometry.cell_center(geometry.cell_of(cells[i]));
    path.poses.push_back({c.x(), c.y(), 0.0});
  }
  // A search that ended short of the goal's own cell (goal_tolerance_m) passes its last cell.
  const auto goal_cell = geometry.world_to_cell(goal.x, goal.y);
  if (cells.size() > 1 && (!goal_cell || geometry.index(*goal_cell) != cells.back())) {
    const Eigen::Vector2d c = geometry.cell_center(geometry.cell_of(cells.back()));
    path.poses.push_back({c.x(), c.y(), 0.0});
  }
  path.poses.push_back(goal);
  for (std::size_t i = 1; i + 1 < path.poses.size(); ++i) {
    const Pose2& next = path.poses[i + 1];
    path.poses[i].theta = std::atan2(next.y - path.poses[i].y, next.x - path.poses[i].x);
  }
  return path;
}

void finish_plan(PlanResult& out, const SearchOutcome& search, const mapping::GridGeometry& geometry,
                 const Endpoints& ends, const Pose2& start, const Pose2& goal, const GlobalPlannerParams& params) {
  out.expansions = search.expansions;
  // An incremental planner (D* Lite) counts the expansions of this call's repair only: 0 when the
  // changes did not reopen what an earlier search found closed.
  const std::string n_exp = std::to_string(search.expansions) + " expansions in this call";
  switch (search.status) {
    case SearchStatus::kTimeout:
      out.result = {Outcome::PLAN_PAT_EXCEEDED,
                    fmt("planning time limit of %.3f ms exceeded after %.0f expansions", params.max_planning_time_ms,
                        static_cast<double>(search.expansions))};
      return;
    case SearchStatus::kNoPath:
      out.result = {Outcome::NO_PATH_FOUND, "no path from start cell " + cell_str(geometry.cell_of(ends.start)) +
                                                " to goal cell " + cell_str(geometry.cell_of(ends.goal)) +
                                                ": the goal is not reachable through traversable cells (" + n_exp +
                                                ")"};
      return;
    case SearchStatus::kFound:
      break;
  }
  out.result = {Outcome::SUCCESS, "path of " + std::to_string(search.cells.size()) + " cells found"};
  out.cost = search.cost;
  out.path = make_world_path(geometry, search.cells, start, goal);
  out.cells.clear();
  for (const std::size_t c : search.cells) out.cells.push_back(geometry.cell_of(c));
}

}  // namespace bipednav::planning::global
