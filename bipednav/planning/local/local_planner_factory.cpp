#include "bipednav/planning/local/local_planner_factory.hpp"

#include <string>
#include <utility>

#include "bipednav/common/error.hpp"
#include "bipednav/planning/local/teb_planner.hpp"
#include "bipednav/planning/local/tracker.hpp"

namespace bipednav::planning::local {

std::unique_ptr<LocalPlanner> make_local_planner(std::string_view name, const LocalPlannerParams& params,
                                                 const MovingObstacleTracker* moving) {
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
    if (key != name) continue;
    auto planner = make(params);
    planner->set_avoidance_params(params.avoidance);
    planner->set_moving_obstacles(moving);
    return planner;
  }
  throw ParamError("local_planner", "\"teb\" or \"tracker\", got \"" + std::string(name) + "\"");
}

}  // namespace bipednav::planning::local
