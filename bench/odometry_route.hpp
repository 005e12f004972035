#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/sim/scenario.hpp"

// The route `bipednav odometry` (on a scenario) and `bench localization`'s LOAM rows drive the
// simulated robot along, and the steering that follows it.
namespace bipednav::bench {

// The route and how it was chosen: explicit waypoints; else the widest route of the scenario's
// static world from its start through its goals in turn (sim::widest_route, the search `bipednav
// route` reports on), thinned to waypoints 0.75 m apart; a scenario without goals: straight ahead.
struct OdometryRoute {
  std::vector<Eigen::Vector2d> waypoints;
  std::string source;  // "waypoints", "widest_route" or "straight (no goal)"
};

// `waypoints` as 'x,y x,y ...' (empty: the widest route, or straight ahead). Throws Error for
// malformed waypoints and for a goal the widest route cannot reach.
OdometryRoute route_for(const std::string& waypoints, const sim::Scenario& s, const RobotProfile& robot);

// Turns towards `goal` (at most 0.8 rad/s) and drives at `v` once it faces it within 0.5 rad.
Twist steer(const Pose2& pose, const Eigen::Vector2d& goal, double v);

}  // namespace bipednav::bench
