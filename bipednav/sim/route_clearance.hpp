#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/sim/collision.hpp"
#include "bipednav/sim/scenario.hpp"
#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

// The widest route of a world's static geometry between two points: whether a robot of a given
// footprint can get from start to goal at all, and with how much room, before any sensing or
// planning is involved (the ground truth a closed-loop result is judged against).
struct RouteClearanceParams {
  double resolution_m = 0.01;  // grid of candidate centre positions; the answer is within ~1 cell
  double height_m = 1.0;       // the robot's height: obstacles are what the slab meets
  CollisionParams collision;   // its ground clearance (as the simulator's collision check)
  // Also find a path along the widest route (RouteClearance::path): a second search over the cells
  // that keep widest_m, shortest with a penalty near obstacles.
  bool with_path = false;

  void validate() const;
  // A robot's slab (its height).
  static RouteClearanceParams for_robot(const RobotProfile& robot);
};

// The room a robot needs between its route's centre line and the obstacles: its footprint radius
// plus a walker's sway, as the simulator's collision check sees the body.
inline double needed_clearance_m(const RobotProfile& robot) {
  return robot.footprint_radius_m + robot.sway_amplitude_m;
}

struct RouteClearance {
  // Whether start and goal lie in the search area and are joined by a route whose centre keeps a
  // positive distance from every obstacle.
  bool connected = false;
  // The largest distance from the route's centre line to the nearest obstacle that a route from
  // start to goal can keep everywhere (the widest disc that gets through; grid cell centres, 8
  // neighbours, exact distances to the obstacles' footprints). 0 when not connected, +infinity
  // without any obstacle.
  double widest_m = 0.0;
  Eigen::Vector2d bottleneck{0, 0};  // where the widest route is narrowest
  std::string bottleneck_obstacle;   // the nearest obstacle there ("" without obstacles)
  std::size_t cells_searched = 0;
  // With RouteClearanceParams::with_path, a route that keeps widest_m: grid cell centres from the
  // start's cell to the goal's, 8-connected, the shortest with each step's length weighted by
  // 1 + 1 m / clearance (it keeps to the middle of passages). Empty when not connected.
  std::vector<Eigen::Vector2d> path;
};

// Waypoints along a path: its points at least spacing_m apart along it, and its last point (a
// path of one point gives that point; an empty one none).
std::vector<Eigen::Vector2d> route_waypoints(const std::vector<Eigen::Vector2d>& path, double spacing_m);

// The axis-aligned search area (the route stays inside it).
struct RouteArea {
  Eigen::Vector2d min{0, 0}, max{0, 0};
};

// Widest route (max-min clearance, a bottleneck Dijkstra) from start to goal through `area` among
// the world's static geometry; actors are ignored (they move). Throws ParamError for bad params
// or a non-finite or empty area.
RouteClearance widest_route(const World& world, const RouteArea& area, const Eigen::Vector2d& start,
                            const Eigen::Vector2d& goal, const RouteClearanceParams& params = {});
// The same from one start to several goals (one result per goal, in their order), sharing the
// footprints and the clearances computed.
std::vector<RouteClearance> widest_routes(const World& world, const RouteArea& area, const Eigen::Vector2d& start,
                                          const std::vector<Eigen::Vector2d>& goals,
                                          const RouteClearanceParams& params = {});

// The widest route from a scenario's start to each of its goals (in their order) within its bounds.
std::vector<RouteClearance> scenario_routes(const Scenario& scenario, const RouteClearanceParams& params = {});

}  // namespace bipednav::sim
