#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/sim/scenario.hpp"
#include "bipednav/sim/simulation.hpp"

// `bipednav sim`: the simulator driven open-loop, without the navigator.
namespace bipednav::runner {

struct OpenLoopOptions {
  double duration_s = 30.0;  // simulated time
  bool progress = false;     // a progress bar on stderr (shown only when it is a terminal)
};

// Drives `robot` from the scenario's start through its world with the scenario's scripted commands
// (a straight line at half the robot's top speed when it has none) for `duration_s`, at `params`'
// step and seed. Writes `figure_png`: the statics shaded by height, the last LiDAR sweep and depth
// image in the world frame (each point from the pose at its firing time), the driven path, start,
// goals, the robot at the end and each contact, with a legend, a scale bar and the height ramp.
// Returns the summary: {scenario, world, robot, seed, duration_s, step_s, steps, commands,
// distance_m, start, final_pose, final_goal_distance_m, collision_count, collisions [{time_s,
// robot, contact_x_m, contact_y_m, obstacle}], min_clearance_m, the sensors' message and point
// counts, lidar_ms, depth_ms, wall_time_s, real_time_factor}.
nlohmann::json run_open_loop(const sim::Scenario& scenario, const RobotProfile& robot,
                             const sim::SimulationParams& params, const OpenLoopOptions& options,
                             const std::filesystem::path& figure_png);

}  // namespace bipednav::runner
