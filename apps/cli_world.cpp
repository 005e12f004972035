#include "apps/cli_world.hpp"

#include <filesystem>

#include "apps/cli_pose.hpp"
#include "bipednav/sim/scenario_files.hpp"

namespace bipednav::app {

sim::Scenario scenario_from_world(const std::string& world_file, const std::string& robot, const std::string& start,
                                  const std::string& goal) {
  return sim::scenario_from_world(std::filesystem::path(world_file), robot, parse_pose(start, "--start"),
                                  parse_pose(goal, "--goal"));
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
