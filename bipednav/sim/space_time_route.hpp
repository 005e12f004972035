#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <limits>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/sim/collision.hpp"
#include "bipednav/sim/route_clearance.hpp"
#include "bipednav/sim/scenario.hpp"
#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

// Whether any robot of a given radius and top speed could reach the goal among a world's people
// without being touched, knowing exactly where each of them will be: the space-time counterpart of
// widest_route. The people follow their scripts blind to the robot, so a world can be impossible
// even though its static route is wide (a person pacing a corridor narrower than person and robot
// side by side, with nowhere to step aside). A navigator's success on a world is judged against
// this answer.
//
// The oracle is optimistic about the body and exact about the people: the robot is a disc that
// moves in any direction at up to its top speed at once (no turning, no acceleration limit, no
// sensing), on a grid of cell centres. Time runs in steps of dt = 2 * resolution / top speed; in
// one step the robot stays or moves to a cell at most two cells away (the 12 such cells), and the
// cells it leaves, crosses and reaches must keep radius + margin from every person during the
// whole step (the people sampled every sample_step_s) and from the static world. The reachable
// cells are propagated step by step from the start (a breadth-first sweep of the space-time grid),
// so the answer is exact for that grid: no search order or heuristic is involved.
struct SpaceTimeRouteParams {
  double resolution_m = 0.05;
  double margin_m = 0.0;        // kept from people and static obstacles beyond the robot's radius
  double sample_step_s = 0.05;  // people's poses within a step are sampled at most this far apart
  double height_m = 1.0;        // the robot's height: obstacles are what the slab meets
  CollisionParams collision;    // its ground clearance (as the simulator's collision check)

  void validate() const;
};

struct SpaceTimeRoute {
  // A cell within the goal tolerance is reachable, and the robot can stay in one untouched until
  // the time limit.
  bool reachable = false;
  // The earliest time the robot can be within the goal tolerance (+infinity when never).
  double arrival_s = std::numeric_limits<double>::infinity();
  // The same without the people: the static world's fastest time at this top speed.
  double static_arrival_s = std::numeric_limits<double>::infinity();
  double step_s = 0.0;    // dt
  std::size_t cells = 0;  // cells of the grid
};

// The robot starts at `start` at time 0 and must be within goal_tolerance_m of `goal` from some
// time on until time_limit_s, never closer than radius_m + margin to a person or a static
// obstacle. Throws ParamError for bad parameters, a non-finite or empty area, a non-positive
// radius, speed or time limit.
SpaceTimeRoute space_time_route(const World& world, const RouteArea& area, const Eigen::Vector2d& start,
                                const Eigen::Vector2d& goal, double goal_tolerance_m, double radius_m,
                                double max_speed_mps, double time_limit_s, const SpaceTimeRouteParams& params = {});

// A scenario's last goal for a robot: its radius as the simulator's collision check sees the body
// (needed_clearance_m), its forward top speed, height, bounds, goal tolerance and time limit.
SpaceTimeRoute scenario_space_time_route(const Scenario& scenario, const RobotProfile& robot,
                                         SpaceTimeRouteParams params = {});

}  // namespace bipednav::sim
