#include "bipednav/sim/scenario_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/sdf_world.hpp"
#include "bipednav/sim/world_drawing.hpp"

#ifndef BIPEDNAV_SCENARIO_DIR
#define BIPEDNAV_SCENARIO_DIR "scenarios"
#endif

namespace bipednav::sim {

std::filesystem::path scenario_dir() { return std::filesystem::path(BIPEDNAV_SCENARIO_DIR); }

std::filesystem::path resolve_scenario(const std::string& name) {
  if (std::filesystem::exists(name)) return name;
  const auto p = scenario_dir() / (name + ".yaml");
  if (std::filesystem::exists(p)) return p;
  throw Error("no scenario '" + name + "' (neither a file nor scenarios/" + name + ".yaml)");
}

std::vector<std::filesystem::path> world_model_paths(const std::filesystem::path& world_file) {
  std::vector<std::filesystem::path> paths;
  if (const char* env = std::getenv("GAZEBO_MODEL_PATH")) {
    std::stringstream ss(env);
    for (std::string dir; std::getline(ss, dir, ':');)
      if (!dir.empty()) paths.emplace_back(dir);
  }
  paths.push_back(world_file.parent_path() / "../models");
  paths.push_back(scenario_dir() / "worlds");
  paths.push_back(scenario_dir() / "worlds" / "turtlebot3" / "models");
  return paths;
}

Scenario scenario_from_world(const std::filesystem::path& file, const std::string& robot, const Pose2& start,
                             const Pose2& goal) {
  Scenario s;
  s.name = file.stem().string();
  s.world = load_sdf_world(file, world_model_paths(file));
  s.robot = robot.empty() ? "turtlebot3" : robot;
  s.start = start;
  s.goals = {{0.0, goal}};
  s.time_limit_s = 180.0;
  const Bounds2 b = world_bounds(s.world);
  s.bounds = {std::min({b.min_x_m, s.start.x, s.goals[0].pose.x}), std::min({b.min_y_m, s.start.y, s.goals[0].pose.y}),
              std::max({b.max_x_m, s.start.x, s.goals[0].pose.x}), std::max({b.max_y_m, s.start.y, s.goals[0].pose.y})};
  s.validate();
  return s;
}

}  // namespace bipednav::sim
