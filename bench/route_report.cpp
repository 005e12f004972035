#include "bench/route_report.hpp"

#include <algorithm>
#include <limits>

#include "bench/json_figures.hpp"
#include "bipednav/sim/route_clearance.hpp"

namespace bipednav::bench {

nlohmann::json route_report(const sim::Scenario& scenario, const RobotProfile& robot, double resolution_m) {
  sim::RouteClearanceParams p = sim::RouteClearanceParams::for_robot(robot);
  p.resolution_m = resolution_m;
  const double needed = sim::needed_clearance_m(robot);
  nlohmann::json routes = nlohmann::json::array();
  double min_margin = std::numeric_limits<double>::infinity();
  const auto found = sim::scenario_routes(scenario, p);
  for (std::size_t i = 0; i < found.size(); ++i) {
    const sim::RouteClearance& c = found[i];
    const double margin = c.connected ? c.widest_m - needed : -needed;
    min_margin = std::min(min_margin, margin);
    const Pose2& goal = scenario.goals[i].pose;
    routes.push_back({{"goal", {goal.x, goal.y}},
                      {"connected", c.connected},
                      {"widest_m", finite_or_null(c.widest_m)},
                      {"margin_m", finite_or_null(margin)},
                      {"bottleneck", {c.bottleneck.x(), c.bottleneck.y()}},
                      {"bottleneck_obstacle", c.bottleneck_obstacle}});
  }
  return {{"scenario", scenario.name},    {"robot", robot.name}, {"needed_m", needed},
          {"resolution_m", resolution_m}, {"routes", routes},    {"min_margin_m", finite_or_null(min_margin)}};
}

}  // namespace bipednav::bench
