#include "bipednav/planning/global/global_planner_factory.hpp"

#include <functional>
#include <utility>

#include "bipednav/common/error.hpp"
#include "bipednav/planning/global/astar.hpp"
#include "bipednav/planning/global/dstar_lite_planner.hpp"

namespace bipednav::planning::global {
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

}  // namespace bipednav::planning::global
