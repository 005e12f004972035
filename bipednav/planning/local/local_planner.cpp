#include "bipednav/planning/local/local_planner.hpp"

#include <functional>
#include <string>
#include <utility>

#include "bipednav/common/error.hpp"
#include "bipednav/planning/local/plan_utils.hpp"
#include "bipednav/planning/local/teb_planner.hpp"
#include "bipednav/planning/local/tracker.hpp"

namespace bipednav::planning::local {

void LocalPlannerParams::validate() const {
  teb.validate();
  tracker.validate();
}

std::optional<LocalPlanResult> reject_bad_inputs(const Pose2& T_map_base, const Twist& current_velocity,
                                                 const Path& global_plan, const mapping::Costmap2D& local_costmap) {
  auto bad = check_inputs(T_map_base, current_velocity, global_plan, local_costmap);
  if (!bad) return std::nullopt;
  LocalPlanResult r;
  r.result = *bad;
  r.trajectory.frame_id = global_plan.frame_id;
  return r;
}

std::unique_ptr<LocalPlanner> make_local_planner(std::string_view name, const LocalPlannerParams& params) {
  using Maker = std::unique_ptr<LocalPlanner> (*)(const LocalPlannerParams&);
  static constexpr std::pair<std::string_view, Maker> kTable[] = {
      {"teb",
       [](const LocalPlannerParams& p) -> std::unique_ptr<LocalPlanner> {
         return std::make_unique<TebPlanner>(p.teb);
       }},
      {"tracker",
       [](const LocalPlannerParams& p) -> std::unique_ptr<LocalPlanner> {
         return std::make_unique<PathTracker>(p.tracker);
       }},
  };
  for (const auto& [key, make] : kTable) {
    if (key == name) return make(params);
  }
  throw ParamError("local_planner", "\"teb\" or \"tracker\", got \"" + std::string(name) + "\"");
}

}  // namespace bipednav::planning::local
