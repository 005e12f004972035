#include "apps/scenario_files.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "apps/cli_pose.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/sim/sdf_world.hpp"
#include "bipednav/sim/world_drawing.hpp"

#ifndef BIPEDNAV_SOURCE_DIR
#define BIPEDNAV_SOURCE_DIR "."
#endif

namespace bipednav::app {

std::filesystem::path scenario_dir() { return std::filesystem::path(BIPEDNAV_SOURCE_DIR) / "scenarios"; }

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

sim::Scenario scenario_from_world(const std::string& world_file, const std::string& robot, const std::string& start,
                                  const std::string& goal) {
  return scenario_from_world(std::filesystem::path(world_file), robot, parse_pose(start, "--start"),
                             parse_pose(goal, "--goal"));
}

sim::Scenario scenario_from_world(const std::filesystem::path& file, const std::string& robot, const Pose2& start,
                                  const Pose2& goal) {
  sim::Scenario s;
  s.name = file.stem().string();
  s.world = sim::load_sdf_world(file, world_model_paths(file));
  s.robot = robot.empty() ? "turtlebot3" : robot;
  s.start = start;
  s.goals = {{0.0, goal}};
  s.time_limit_s = 180.0;
  const sim::Bounds2 b = sim::world_bounds(s.world);
  s.bounds = {std::min({b.min_x_m, s.start.x, s.goals[0].pose.x}), std::min({b.min_y_m, s.start.y, s.goals[0].pose.y}),
              std::max({b.max_x_m, s.start.x, s.goals[0].pose.x}), std::max({b.max_y_m, s.start.y, s.goals[0].pose.y})};
  s.validate();
  return s;
}

void add_world_options(CLI::App* command, CLI::Option* scenario, std::string& world, std::string& start,
                       std::string& goal) {
  CLI::Option* w =
      command->add_option("--world", world, "A Gazebo .world file instead of a scenario")->check(CLI::ExistingFile);
  CLI::Option* s = command->add_option("--start", start, "With --world (required): start pose x,y[,yaw]");
  CLI::Option* g = command->add_option("--goal", goal, "With --world (required): goal pose x,y[,yaw]");
  w->needs(s, g)->excludes(scenario);
  s->needs(w);
  g->needs(w);
}

}  // namespace bipednav::app
