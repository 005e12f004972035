#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/planning/global/global_planner.hpp"
#include "bipednav/planning/global/grid_cost_model.hpp"
#include "bipednav/planning/global/indexed_heap.hpp"
#include "bipednav/planning/global/search_types.hpp"

namespace bipednav::planning::global {

// A* on the 8-connected grid with the GridCostModel's edge costs and octile heuristic. Keeps its
// arrays between searches so repeated searches do not reallocate.
class AStar {
 public:
  SearchOutcome search(const GridCostModel& model, std::size_t start, std::size_t goal, const Deadline& deadline);

 private:
  std::vector<Cost> g_;
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint8_t> closed_;
  IndexedHeap open_;
};

// The baseline global planner: plans from scratch on every call (the change set is ignored).
class AStarPlanner : public GlobalPlanner {
 public:
  explicit AStarPlanner(const GlobalPlannerParams& params = {});
  PlanResult plan(const mapping::Costmap2D& map, const Pose2& start, const Pose2& goal,
                  const mapping::ChangeSet& changes_since_last_call) override;
  void reset() override {}
  std::string name() const override { return "astar"; }

 private:
  GlobalPlannerParams params_;
  GridCostModel model_;
  AStar astar_;
};

}  // namespace bipednav::planning::global
