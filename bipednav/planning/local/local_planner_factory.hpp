#pragma once

#include <memory>
#include <string_view>

#include "bipednav/planning/local/local_planner.hpp"

namespace bipednav::planning::local {

// Factory table: "teb" or "tracker"; throws ParamError for another name.
// `moving`: the tracked moving obstacles the planner yields to (set_moving_obstacles); nullptr, said
// explicitly, for a planner that yields to none.
std::unique_ptr<LocalPlanner> make_local_planner(std::string_view name, const LocalPlannerParams& params,
                                                 const MovingObstacleTracker* moving);

}  // namespace bipednav::planning::local
