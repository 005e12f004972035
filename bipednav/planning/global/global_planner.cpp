#include "bipednav/planning/global/global_planner.hpp"

#include <cmath>
#include <cstdio>
#include <functional>
#include <utility>

#include "bipednav/common/error.hpp"
#include "bipednav/planning/global/astar.hpp"
#include "bipednav/planning/global/dstar_lite_planner.hpp"

namespace bipednav::planning {

void GlobalPlannerParams::validate() const {
  cost.validate();
  require(std::isfinite(max_planning_time_ms) && max_planning_time_ms >= 0.0, "max_planning_time_ms",
          "a finite value >= 0 (0 = no limit)");
}

namespace {

using Factory = std::function<std::unique_ptr<GlobalPlanner>(const GlobalPlannerParams&)>;

// The explicit table of global planners (no static registration).
const std::vector<std::pair<std::string, Factory>>& planner_table() {
  static const std::vector<std::pair<std::string, Factory>> table = {
      {"dstar_lite", [](const GlobalPlannerParams& p) { return std::make_unique<DStarLitePlanner>(p); }},
      {"astar", [](const GlobalPlannerParams& p) { return std::make_unique<AStarPlanner>(p); }},
  };
  return table;
}

std::string fmt(const char* f, double a, double b) {
  char buf[96];
  std::snprintf(buf, sizeof(buf), f, a, b);
  return buf;
}

std::string cell_str(const mapping::Cell& c) {
  char buf[48];
  std::snprintf(buf, sizeof(buf), "(%d, %d)", c.x, c.y);
  return buf;
}

std::string cost_str(std::uint8_t c) {
  if (c == mapping::kLethal) return "254 (lethal)";
  if (c == mapping::kInscribed) return "253 (inscribed: the robot's centre may not stand there)";
  if (c == mapping::kUnknown) return "255 (unknown, and unknown cells are obstacles)";
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

std::unique_ptr<GlobalPlanner> make_global_planner(const std::string& name, const GlobalPlannerParams& params) {
  for (const auto& [n, make] : planner_table())
    if (n == name) return make(params);
  std::string names;
  for (const auto& n : global_planner_names()) names += (names.empty() ? "" : " | ") + n;
  throw ParamError("global_planner", "one of " + names + " (got '" + name + "')");
}

std::vector<std::string> global_planner_names() {
  std::vector<std::string> out;
  for (const auto& entry : planner_table()) out.push_back(entry.first);
  return out;
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
  if (!std::isfinite(cell_factor(gc, params.cost))) {
    failure = {Outcome::BLOCKED_GOAL, "goal cell " + cell_str(*t) + " has cost " + cost_str(gc)};
    return std::nullopt;
  }
  Endpoints e{g.index(*s), g.index(*t), false};
  if (!std::isfinite(cell_factor(sc, params.cost))) {
    if (sc == mapping::kLethal || !params.allow_start_in_inscribed) {
      failure = {Outcome::BLOCKED_START, "start cell " + cell_str(*s) + " has cost " + cost_str(sc) +
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
  const std::string n_exp = std::to_string(search.expansions) + " expansions";
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

}  // namespace bipednav::planning
