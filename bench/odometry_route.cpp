#include "bench/odometry_route.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/sim/route_clearance.hpp"

namespace bipednav::bench {
namespace {

constexpr double kRouteSpacingM = 0.75;
constexpr double kRouteResolutionM = 0.05;

}  // namespace

OdometryRoute route_for(const std::string& waypoints, const sim::Scenario& s, const RobotProfile& robot) {
  OdometryRoute route;
  std::istringstream in(waypoints);
  std::string item;
  while (in >> item) {
    double x = 0, y = 0;
    if (std::sscanf(item.c_str(), "%lf,%lf", &x, &y) != 2)
      throw Error("--waypoints: expected 'x,y x,y ...', got '" + item + "'");
    route.waypoints.emplace_back(x, y);
  }
  if (!route.waypoints.empty()) {
    route.source = "waypoints";
    return route;
  }
  if (s.goals.empty()) {
    const double c = std::cos(s.start.theta), sn = std::sin(s.start.theta);
    route.waypoints = {{s.start.x + 100.0 * c, s.start.y + 100.0 * sn}};
    route.source = "straight (no goal)";
    return route;
  }
  sim::RouteClearanceParams p = sim::RouteClearanceParams::for_robot(robot);
  p.resolution_m = kRouteResolutionM;
  p.with_path = true;
  const sim::RouteArea area{{s.bounds.min_x_m, s.bounds.min_y_m}, {s.bounds.max_x_m, s.bounds.max_y_m}};
  Eigen::Vector2d from = s.start.position();
  for (const sim::TimedGoal& g : s.goals) {
    const sim::RouteClearance r = sim::widest_route(s.world, area, from, g.pose.position(), p);
    if (!r.connected)
      throw Error("scenario '" + s.name + "': no route from (" + std::to_string(from.x()) + ", " +
                  std::to_string(from.y()) + ") to its goal (" + std::to_string(g.pose.x) + ", " +
                  std::to_string(g.pose.y) + "); give --waypoints");
    for (const Eigen::Vector2d& w : sim::route_waypoints(r.path, kRouteSpacingM)) route.waypoints.push_back(w);
    route.waypoints.back() = g.pose.position();  // the goal itself, not its grid cell
    from = g.pose.position();
  }
  route.source = "widest_route";
  return route;
}

Twist steer(const Pose2& pose, const Eigen::Vector2d& goal, double v) {
  const Eigen::Vector2d d = goal - pose.position();
  const double heading_error = angle_diff(std::atan2(d.y(), d.x()), pose.theta);
  Twist t;
  t.angular_z = std::clamp(1.5 * heading_error, -0.8, 0.8);
  t.linear_x = std::abs(heading_error) < 0.5 ? v : 0.0;
  return t;
}

}  // namespace bipednav::bench
