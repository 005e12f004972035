#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/outcome.hpp"
#include "bipednav/common/path.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/planning/global/grid_cost_model.hpp"
#include "bipednav/planning/global/search_types.hpp"

namespace bipednav::planning::global {

struct GlobalPlannerParams {
  GridCostParams cost;
  // Lets the search leave a start cell that is inscribed or unknown (the robot standing close to
  // an obstacle); a lethal start cell is always BLOCKED_START.
  bool allow_start_in_inscribed = true;
  // A goal whose cell is inscribed (the robot's centre may not stand there) but not lethal is
  // planned to the traversable cell nearest to it whose centre lies within this distance, as
  // NavFn's and Smac's `tolerance` do; the path still ends at the goal pose, so the controller
  // and the goal checker keep aiming at the goal itself. A map that thickens a wall by a cell next
  // to a goal near it then no longer ends the run in BLOCKED_GOAL. 0 = an inscribed goal is
  // BLOCKED_GOAL; a lethal goal cell always is.
  double goal_tolerance_m = 0.1;
  double max_planning_time_ms = 0.0;  // 0 = no limit; otherwise PLAN_PAT_EXCEEDED past it
  // D* Lite: compare its map snapshot with the given map and repair cells missing from the
  // change set (costs one pass over the grid's bytes).
  bool verify_changes = true;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v.group("cost", cost);
    v("allow_start_in_inscribed", allow_start_in_inscribed);
    v("goal_tolerance_m", goal_tolerance_m);
    v("max_planning_time_ms", max_planning_time_ms);
    v("verify_changes", verify_changes);
  }
};

struct PlanResult {
  Result result;      // SUCCESS, NO_PATH_FOUND, BLOCKED_START, BLOCKED_GOAL, PLAN_OUT_OF_MAP, PLAN_PAT_EXCEEDED
  Path path;          // start pose, cell centres, goal pose (with the goal's yaw)
  double cost = 0.0;  // path cost under the cost model (m x factor); length for unit costs
  std::size_t expansions = 0;        // vertices expanded in this call
  double time_ms = 0.0;              // wall time of this call
  std::vector<mapping::Cell> cells;  // the cell path, start cell first
};

// One global planning algorithm on a 2D costmap. Implementations keep state between calls:
// `changes_since_last_call` lists cells changed since the previous call (an incremental planner
// repairs its search with them when the goal and grid geometry are unchanged).
class GlobalPlanner {
 public:
  virtual ~GlobalPlanner() = default;
  virtual PlanResult plan(const mapping::Costmap2D& map, const Pose2& start, const Pose2& goal,
                          const mapping::ChangeSet& changes_since_last_call) = 0;
  // Forgets all search state; the next plan() starts from scratch.
  virtual void reset() = 0;
  virtual std::string name() const = 0;
};

// ---- helpers shared by the implementations ----

// The cell a search for `goal` ends in: the goal's own cell when the cost model can enter it;
// for an inscribed (not lethal) goal cell, the enterable cell whose centre is nearest to the goal
// point within params.goal_tolerance_m (ties: the first in row-major order); nullopt otherwise,
// and when the goal is off the map.
std::optional<mapping::Cell> goal_search_cell(const mapping::Costmap2D& map, const Pose2& goal,
                                              const GlobalPlannerParams& params);

// Start and goal resolved to cells, or the failure outcome explaining why not.
struct Endpoints {
  std::size_t start = 0;
  std::size_t goal = 0;
  bool start_exempt = false;  // the start cell is impassable but may be left
};
std::optional<Endpoints> resolve_endpoints(const mapping::Costmap2D& map, const Pose2& start, const Pose2& goal,
                                           const GlobalPlannerParams& params, Result& failure);

// World path from a cell path: the start pose, the centres of the cells between, the goal pose;
// intermediate yaws point to the next pose, the goal keeps its yaw. When the search ended in a
// cell other than the goal's (goal_tolerance_m), that cell's centre comes before the goal pose.
Path make_world_path(const mapping::GridGeometry& geometry, const std::vector<std::size_t>& cells, const Pose2& start,
                     const Pose2& goal);

// Turns a search outcome into the plan's result (reason message), path, cells and cost.
void finish_plan(PlanResult& out, const SearchOutcome& search, const mapping::GridGeometry& geometry,
                 const Endpoints& ends, const Pose2& start, const Pose2& goal, const GlobalPlannerParams& params);

}  // namespace bipednav::planning::global
