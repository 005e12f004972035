#pragma once

#include <nlohmann/json.hpp>
#include <string>

// `bipednav odometry SCENARIO`: LOAM's and the raw odometry's drift while the simulated robot drives
// a scenario's route (bench/odometry_route).
namespace bipednav::bench {

struct ScenarioOdometryOptions {
  std::string scenario;     // the scenario's YAML file
  std::string config_dir;   // robot profiles (empty: the installed config/)
  std::string waypoints;    // 'x,y x,y ...' (empty: the widest route through the goals, or straight ahead)
  double duration_s = 0.0;  // 0: until the route is done (or the scenario's time limit)
  double speed_mps = 0.0;   // 0: the robot's maximum
  bool no_prior = false;    // LOAM without the odometry as its motion prior
  bool planar = false;      // LOAM keeps the LiDAR's height, roll and pitch (LoamParams::planar_motion)
  std::string params;       // a navigation parameters file: LOAM's parameters from its localization.loam
};

// Drives the scenario's robot (its VLP-16 mount named 'lidar', depth off) along the route, runs
// LOAM on every sweep (with the wheel or leg odometry's increment as the prior) and returns the
// drift of LOAM and of the raw odometry against the simulator's truth: {scenario, simulated_s,
// distance_m, sweeps, route, route_waypoints, route_completed, contacts, motion_prior,
// planar_motion, unhealthy_sweeps, degenerate_sweeps, loam {...}, odometry {...},
// loam_odometry_mean_ms, loam_mapping_mean_ms}. Throws Error for a robot without such a LiDAR, a
// malformed route, or a run too short for one sweep.
nlohmann::json run_scenario_odometry(const ScenarioOdometryOptions& options);

}  // namespace bipednav::bench
