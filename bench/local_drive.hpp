#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bipednav/common/pose2.hpp"

// `bipednav local plan`: a local planner drives a kinematic unicycle along D* Lite's global plan on
// a map_server map, and the run is drawn.
namespace bipednav::bench {

struct LocalDriveOptions {
  std::string map;  // map_server YAML
  Pose2 start, goal;
  std::string out;              // PNG of the run (empty: none)
  std::string planner = "teb";  // teb | tracker
  int steps = 600;              // control cycles at most
  int threads = 1;              // threads for TEB's homotopy candidates
};

// Plans D* Lite on the map inflated with the global costmap's defaults (as the navigation server
// hands a plan over), then drives the robot with the local planner in an 8 m window of the map,
// integrating each command exactly for one control period, until the planner reports the goal
// reached or `steps` cycles pass. Returns {planner, global_plan {outcome, message, length_m},
// reached, last_outcome, cycles, time_s, final_pose, out}; writes the figure (map, global plan,
// driven path, last local trajectory, start, goal, robot) to `out`. Throws Error for an unreadable
// map or bad parameters.
nlohmann::json run_local_drive(const LocalDriveOptions& options);

}  // namespace bipednav::bench
