#include "bipednav/sim/placement_check.hpp"

#include <cstdio>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/collision.hpp"

namespace bipednav::sim {

namespace {

std::string metres(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.2f", v);
  return s;
}

std::string obstacle_name(const std::string& name) { return name.empty() ? "an unnamed obstacle" : "'" + name + "'"; }

}  // namespace

std::optional<std::string> placement_problem(const Scenario& scenario, const RobotProfile& robot, const Pose2& where,
                                             const std::string& what, const PlacementCheckParams& params) {
  require(std::isfinite(params.tolerance_m) && params.tolerance_m >= 0.0, "tolerance_m", ">= 0 m");
  const std::string at = what + " (" + metres(where.x) + ", " + metres(where.y) + ")";
  const Bounds& b = scenario.bounds;
  if (!where.is_finite() || !b.contains(where.x, where.y))
    return at + " is off the map (x " + metres(b.min_x_m) + " to " + metres(b.max_x_m) + " m, y " + metres(b.min_y_m) +
           " to " + metres(b.max_y_m) + " m)";
  if (!params.check_obstacles) return std::nullopt;
  World statics = scenario.world;
  statics.actors.clear();
  const CollisionChecker checker(statics, robot.footprint_radius_m, robot.height_m);
  const Proximity p = checker.nearest(where.position(), 0.0);
  const double centre_m = p.clearance_m + robot.footprint_radius_m;  // centre to the obstacle
  if (centre_m <= 0.0) return at + " is inside " + obstacle_name(p.obstacle);
  if (p.clearance_m < -params.tolerance_m)
    return at + " is " + metres(centre_m) + " m from " + obstacle_name(p.obstacle) + " (nearest point (" +
           metres(p.point.x()) + ", " + metres(p.point.y()) + ")); the robot's footprint needs " +
           metres(robot.footprint_radius_m) + " m" +
           (params.tolerance_m > 0 ? ", less the tolerance " + metres(params.tolerance_m) + " m" : std::string());
  return std::nullopt;
}

void check_placements(const Scenario& scenario, const RobotProfile& robot, bool check_obstacles) {
  std::string problems;
  const auto add = [&](const std::optional<std::string>& p) {
    if (p) problems += (problems.empty() ? "" : "; ") + *p;
  };
  add(placement_problem(scenario, robot, scenario.start, "the start", {0.0, check_obstacles}));
  for (std::size_t i = 0; i < scenario.goals.size(); ++i) {
    const std::string what = scenario.goals.size() == 1 ? "the goal" : "goal " + std::to_string(i + 1);
    add(placement_problem(scenario, robot, scenario.goals[i].pose, what, {scenario.goal_tolerance_m, check_obstacles}));
  }
  if (!problems.empty()) throw Error(scenario.name + " with " + robot.name + ": " + problems);
}

}  // namespace bipednav::sim
