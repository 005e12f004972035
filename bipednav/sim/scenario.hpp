#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/sim/fault.hpp"
#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

// A goal handed to the robot at `time_s` (so a goal can change mid-run).
struct TimedGoal {
  double time_s = 0.0;
  Pose2 pose;
};

// A velocity command applied from `time_s` until the next one (for `bipednav sim`).
struct ScriptedCommand {
  double time_s = 0.0;
  Twist twist;
};

// The x/y extent of the world and the robot's start and goals, for sizing maps and figures.
struct Bounds {
  double min_x_m = 0.0, min_y_m = 0.0, max_x_m = 0.0, max_y_m = 0.0;
  double size_x_m() const { return max_x_m - min_x_m; }
  double size_y_m() const { return max_y_m - min_y_m; }
  bool contains(double x, double y) const { return x >= min_x_m && x <= max_x_m && y >= min_y_m && y <= max_y_m; }
};

// One experiment: world, robot, start, goals over time, limits (see scenarios/README.md).
struct Scenario {
  std::string name;
  std::string description;
  World world;
  std::string robot = "turtlebot3";  // profile name: config/<robot>.yaml
  Pose2 start;
  std::vector<TimedGoal> goals;  // sorted by time_s
  double time_limit_s = 120.0;
  std::uint64_t seed = 1;
  std::vector<ScriptedCommand> commands;  // sorted by time_s; may be empty
  double goal_tolerance_m = 0.2;
  double goal_tolerance_rad = 0.2;
  Bounds bounds;
  std::vector<Fault> faults;  // injected on the sensor path and the goal stream (fault.hpp)

  void validate() const;
  // The goal in force at time t (the last one given at or before t); nullptr before the first.
  const TimedGoal* goal_at(double t_s) const;
  // The scripted command in force at time t (zero before the first / without a script).
  Twist command_at(double t_s) const;
};

// Reads a scenario YAML file. The world is either inline (`world:` with walls, boxes, cylinders
// and moving obstacles) or an SDF file (`world_file:`, relative to the scenario file), or both
// (the inline obstacles are added to the SDF world). `model_paths` are searched for `model://`
// URIs, after the scenario's own `model_paths:` entries. Unknown keys, wrong types and invalid
// values raise FileError naming the file and the field.
Scenario load_scenario(const std::filesystem::path& file, const std::vector<std::filesystem::path>& model_paths = {});

}  // namespace bipednav::sim
