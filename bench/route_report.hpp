#pragma once

#include <nlohmann/json.hpp>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/sim/scenario.hpp"

namespace bipednav::bench {

// The report of `route --json` (also each row of `bench scenarios`, and each world's margin in
// `bench worlds`): the widest route of the scenario's static world from its start to each goal,
// against the room the robot needs: the robot's needed clearance, each goal's widest route and
// margin, and the smallest margin.
nlohmann::json route_report(const sim::Scenario& scenario, const RobotProfile& robot, double resolution_m);

}  // namespace bipednav::bench
