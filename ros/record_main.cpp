// bipednav_record SCENARIO --bag FILE.bag: runs a scenario closed-loop (simulator + Navigator,
// no master needed) and records it as a rosbag. ROS-only companion of `bipednav run`.
#include <CLI/CLI.hpp>
#include <iostream>

#include "bipednav/common/error.hpp"
#include "ros/bag_recorder.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Run a bipednav scenario and record it as a rosbag"};
  std::string scenario_file, bag_file = "run.bag";
  bipednav::runner::RunOptions options;
  double time_limit_s = 0.0;
  bipednav::ros1::BagRecorderParams bag;
  app.add_option("scenario", scenario_file, "scenario YAML file")->required()->check(CLI::ExistingFile);
  app.add_option("--bag", bag_file, "output bag file");
  app.add_option("--robot", options.robot, "robot profile name (default: the scenario's)");
  app.add_option("--time-limit", time_limit_s, "simulated seconds (default: the scenario's)");
  app.add_option("--global-planner", options.global_planner, "dstar_lite | astar");
  app.add_option("--local-planner", options.local_planner, "teb | tracker");
  app.add_flag("--depth", bag.record_depth, "also record the depth clouds (large)");
  CLI11_PARSE(app, argc, argv);
  try {
    if (time_limit_s > 0.0) options.time_limit_s = time_limit_s;
    const auto scenario = bipednav::sim::load_scenario(scenario_file);
    const auto s = bipednav::ros1::run_scenario_to_bag(scenario, options, bag_file, bag);
    std::cout << scenario.name << ": " << bipednav::navigation::nav_state_name(s.status.state) << " "
              << bipednav::outcome_name(s.status.result.outcome) << " (" << bipednav::code(s.status.result.outcome)
              << ") " << s.status.result.message << " after " << s.time_s << " s" << (s.collided ? ", COLLISION" : "")
              << "; " << s.messages << " messages written to " << bag_file << "\n";
    return s.status.state == bipednav::navigation::NavState::SUCCEEDED ? 0 : 3;
  } catch (const std::exception& e) {
    std::cerr << "bipednav_record: " << e.what() << "\n";
    return 1;
  }
}
