#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

// `bipednav bench worlds`: many generated worlds (crowd: people where the robot must go; clutter:
// BARN-like post fields), or the cases of a user's cases file, with each robot. Per robot: success,
// contacts while moving and while standing, time-outs (95 % Wilson intervals), the time against
// the same world without its people.
namespace bipednav::bench {

struct WorldBenchOptions {
  std::string family = "crowd";
  std::string cases;  // instead of generated worlds
  int worlds = 20;
  int first_seed = 1;
  int jobs = 1;
  std::vector<std::string> robots{"turtlebot3", "digit"};
  std::string save_worlds;  // directory for the generated .world files and their cases file
  std::string params;       // navigation parameters file (RunOptions::params_file)
};

// Runs every world with each robot (a case with its own robot), and once more without its people,
// `jobs` runs at a time (the results do not depend on `jobs`); writes the generated worlds to
// `save_worlds` when given. Returns {title, family, first_seed, worlds, robots: the figures per
// robot, runs: every run with people}; throws Error for bad options.
nlohmann::json run_world_bench(const WorldBenchOptions& options);

}  // namespace bipednav::bench
