#include "bipednav/planning/global/dstar_lite_planner.hpp"

namespace bipednav::planning::global {

DStarLitePlanner::DStarLitePlanner(const GlobalPlannerParams& params) : params_(params), dstar_(params.cost) {
  params_.validate();
}

bool DStarLitePlanner::can_repair(const mapping::Costmap2D& map, std::size_t goal) const {
  const auto& g = map.geometry();
  return !needs_reset_ && dstar_.initialized() && goal == dstar_.goal() && g == geometry_;
}

std::vector<CellUpdate> DStarLitePlanner::collect_updates(const mapping::Costmap2D& map,
                                                          const mapping::ChangeSet& changes) {
  const auto& model = dstar_.model();
  const auto& now = map.data();
  std::vector<CellUpdate> out;
  queued_.resize(now.size(), 0);
  for (const auto& ch : changes) {
    if (!map.in_bounds(ch.cell.x, ch.cell.y)) continue;
    const std::size_t i = map.geometry().index(ch.cell);
    if (queued_[i] || model.cost(i) == now[i]) continue;  // the map's value is the truth
    queued_[i] = 1;
    out.push_back({i, now[i]});
  }
  last_missed_changes_ = 0;
  if (params_.verify_changes) {
    const auto& snap = model.costs();
    for (std::size_t i = 0; i < now.size(); ++i) {
      if (snap[i] == now[i] || queued_[i]) continue;
      out.push_back({i, now[i]});
      ++last_missed_changes_;
    }
  }
  for (const auto& u : out) queued_[u.index] = 0;
  return out;
}

SearchOutcome DStarLitePlanner::search_and_extract(const Deadline& deadline) {
  std::size_t expansions = 0;
  SearchOutcome out;
  if (dstar_.compute_shortest_path(deadline, expansions) == SearchStatus::kTimeout) {
    out.status = SearchStatus::kTimeout;
  } else {
    out = dstar_.extract_path();
  }
  out.expansions = expansions;
  return out;
}

PlanResult DStarLitePlanner::plan(const mapping::Costmap2D& map, const Pose2& start, const Pose2& goal,
                                  const mapping::ChangeSet& changes_since_last_call) {
  const Stopwatch watch;
  const Deadline deadline(params_.max_planning_time_ms);
  PlanResult out;
  const auto ends = resolve_endpoints(map, start, goal, params_, out.result);
  if (!ends) {
    needs_reset_ = true;  // the change set of this call is not applied, so start afresh next time
    out.time_ms = watch.elapsed_ms();
    return out;
  }
  const std::int64_t exempt = ends->start_exempt ? static_cast<std::int64_t>(ends->start) : -1;
  last_incremental_ = can_repair(map, ends->goal);
  if (last_incremental_) {
    const auto updates = collect_updates(map, changes_since_last_call);
    dstar_.move_start(ends->start);
    if (!updates.empty() || exempt != dstar_.model().exempt()) dstar_.update_cells(updates, exempt);
  } else {
    dstar_.model().assign(map);
    dstar_.model().set_exempt(exempt);
    dstar_.initialize(ends->start, ends->goal);
    geometry_ = map.geometry();
    needs_reset_ = false;
  }
  SearchOutcome s = search_and_extract(deadline);
  if (s.status == SearchStatus::kNoPath && dstar_.rhs(ends->start) < kInfCost) {
    // Path extraction found no descent although the start has a finite distance: recover by
    // searching from scratch rather than returning a wrong answer.
    dstar_.initialize(ends->start, ends->goal);
    const std::size_t before = s.expansions;
    s = search_and_extract(deadline);
    s.expansions += before;
  }
  finish_plan(out, s, map.geometry(), *ends, start, goal, params_);
  out.time_ms = watch.elapsed_ms();
  return out;
}

}  // namespace bipednav::planning::global
