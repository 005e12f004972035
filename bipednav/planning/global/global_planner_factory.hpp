#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bipednav/planning/global/global_planner.hpp"

namespace bipednav::planning::global {

// Explicit factory table: "dstar_lite" or "astar"; anything else raises ParamError.
std::unique_ptr<GlobalPlanner> make_global_planner(const std::string& name, const GlobalPlannerParams& params);
std::vector<std::string> global_planner_names();

}  // namespace bipednav::planning::global
