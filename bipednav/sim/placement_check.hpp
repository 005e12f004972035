#pragma once

#include <optional>
#include <string>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/sim/scenario.hpp"

namespace bipednav::sim {

// Whether a robot can stand at a place of a scenario's static world, checked before a run so
// that a goal inside a wall is reported at once (in metres, naming the obstacle) instead of after
// a minute of recoveries. Actors are ignored (they move).
struct PlacementCheckParams {
  // How far the robot may stay from the place: its footprint may not overlap the static world
  // anywhere within this distance of it (the goal's xy tolerance; 0 for a start).
  double tolerance_m = 0.0;
  // Whether to check the static geometry at all (a humanoid steps over and onto low obstacles, so
  // only the bounds are checked for it).
  bool check_obstacles = true;
};

// Why a robot's footprint (radius, height slab) cannot be at `where` in `scenario`, or nullopt
// when it can: off the scenario's bounds, its centre inside an obstacle, or its footprint
// overlapping an obstacle by more than the tolerance (a disc nearer the obstacle than
// footprint - tolerance cannot be reached within the tolerance). `what` starts the message
// ("goal 1 (3.00, 2.00)").
std::optional<std::string> placement_problem(const Scenario& scenario, const RobotProfile& robot, const Pose2& where,
                                             const std::string& what, const PlacementCheckParams& params = {});

// Checks the scenario's start (tolerance 0) and every goal (the scenario's xy tolerance) and
// throws Error with every problem found.
void check_placements(const Scenario& scenario, const RobotProfile& robot, bool check_obstacles = true);

}  // namespace bipednav::sim
