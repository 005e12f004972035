#include "bipednav/planning/global/astar.hpp"

#include <algorithm>

namespace bipednav::planning::global {

SearchOutcome AStar::search(const GridCostModel& model, std::size_t start, std::size_t goal, const Deadline& deadline) {
  const std::size_t n = model.size();
  g_.assign(n, kInfCost);
  parent_.resize(n);
  closed_.assign(n, 0);
  if (open_.capacity() != n) open_.resize(n);
  open_.clear();

  SearchOutcome out;
  g_[start] = 0.0;
  parent_[start] = static_cast<std::uint32_t>(start);
  const int gx = model.x_of(goal), gy = model.y_of(goal);
  open_.insert(start, {model.heuristic(start, goal), model.heuristic(start, goal)});
  while (!open_.empty()) {
    const std::size_t u = open_.pop();
    if (u == goal) break;
    closed_[u] = 1;
    if (++out.expansions % kDeadlineCheckEvery == 0 && deadline.expired()) {
      out.status = SearchStatus::kTimeout;
      return out;
    }
    const int x = model.x_of(u), y = model.y_of(u);
    for (int k = 0; k < kNumNeighbours; ++k) {
      const Cost c = model.edge_cost(x, y, k);
      if (c >= kInfCost) continue;
      const std::size_t v = model.idx(x + kDx[k], y + kDy[k]);
      if (closed_[v]) continue;
      const Cost gv = g_[u] + c;
      if (gv >= g_[v]) continue;
      g_[v] = gv;
      parent_[v] = static_cast<std::uint32_t>(u);
      const Cost h = model.octile(x + kDx[k] - gx, y + kDy[k] - gy);
      open_.push(v, {gv + h, h});  // ties broken towards the goal
    }
  }
  if (g_[goal] >= kInfCost) return out;
  out.status = SearchStatus::kFound;
  out.cost = model.to_metres(g_[goal]);
  for (std::size_t v = goal; v != start; v = parent_[v]) out.cells.push_back(v);
  out.cells.push_back(start);
  std::reverse(out.cells.begin(), out.cells.end());
  return out;
}

AStarPlanner::AStarPlanner(const GlobalPlannerParams& params) : params_(params), model_(params.cost) {
  params_.validate();
}

PlanResult AStarPlanner::plan(const mapping::Costmap2D& map, const Pose2& start, const Pose2& goal,
                              const mapping::ChangeSet& /*changes_since_last_call*/) {
  const Stopwatch watch;
  const Deadline deadline(params_.max_planning_time_ms);
  PlanResult out;
  const auto ends = resolve_endpoints(map, start, goal, params_, out.result);
  if (!ends) {
    out.time_ms = watch.elapsed_ms();
    return out;
  }
  model_.assign(map);
  if (ends->start_exempt) model_.set_exempt(static_cast<std::int64_t>(ends->start));
  const SearchOutcome s = astar_.search(model_, ends->start, ends->goal, deadline);
  out.expansions = s.expansions;
  finish_plan(out, s, map.geometry(), *ends, start, goal, params_);
  out.time_ms = watch.elapsed_ms();
  return out;
}

}  // namespace bipednav::planning::global
