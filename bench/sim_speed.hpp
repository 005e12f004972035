#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bipednav/sim/depth_camera.hpp"

// `bipednav bench sim`: the simulator's speed with Digit's full sensor suite (a VLP-16 and two depth
// cameras) in a furnished room with a moving box, on one core.
namespace bipednav::bench {

struct SimBenchOptions {
  double duration_s = 20.0;
  std::string robot_file;       // empty: Digit as in config/digit.yaml
  std::string sensors = "all";  // all | lidar | depth
  std::string renderer = sim::DepthCameraParams{}.renderer;
  bool progress = true;  // a progress bar on stderr
};

// Simulates `duration_s` of the robot driving a slow circle through the room, every sensor's rays
// cast anew each frame. Returns the sensors simulated, the simulated time, the CPU and wall real-time
// factors against the 20x goal (`meets_goal`, on process CPU time) and the per-sensor costs; throws
// Error for bad options.
nlohmann::json run_sim_bench(const SimBenchOptions& options);

}  // namespace bipednav::bench
