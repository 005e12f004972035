#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/planning/global/dstar_lite.hpp"
#include "bipednav/planning/global/global_planner.hpp"

namespace bipednav::planning::global {

// D* Lite behind the GlobalPlanner interface (Algorithm 4 spread over plan() calls): the first
// call, a new goal or a new grid geometry (re)initialises the search; later calls move the start,
// apply the changed cells and repair the search incrementally.
class DStarLitePlanner : public GlobalPlanner {
 public:
  explicit DStarLitePlanner(const GlobalPlannerParams& params = {});
  PlanResult plan(const mapping::Costmap2D& map, const Pose2& start, const Pose2& goal,
                  const mapping::ChangeSet& changes_since_last_call) override;
  void reset() override { needs_reset_ = true; }
  std::string name() const override { return "dstar_lite"; }

  // Statistics of the last plan() call.
  bool last_was_incremental() const { return last_incremental_; }
  std::size_t last_missed_changes() const { return last_missed_changes_; }
  const DStarLite& search() const { return dstar_; }

 private:
  bool can_repair(const mapping::Costmap2D& map, std::size_t goal) const;
  // Cells whose snapshot cost differs from `map`: those in `changes`, plus (verify_changes)
  // any the change set missed.
  std::vector<CellUpdate> collect_updates(const mapping::Costmap2D& map, const mapping::ChangeSet& changes);
  SearchOutcome search_and_extract(const Deadline& deadline);

  GlobalPlannerParams params_;
  DStarLite dstar_;
  mapping::GridGeometry geometry_;
  bool needs_reset_ = true;
  bool last_incremental_ = false;
  std::size_t last_missed_changes_ = 0;
  std::vector<std::uint8_t> queued_;
};

}  // namespace bipednav::planning::global
