#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "bipednav/navigation/navigator.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/simulation.hpp"

namespace rosbag {
class Bag;
}

namespace bipednav::ros1 {

struct BagRecorderParams {
  double map_period_s = 0.5;    // global costmap
  double local_period_s = 0.2;  // local costmap, markers
  double path_period_s = 0.2;   // global plan, local trajectory
  bool record_depth = false;    // depth clouds are large (~1 MB each, 15 Hz per camera)
  bool compress = true;         // LZ4 chunks
  std::string map_frame = "map", odom_frame = "odom", base_frame = "base_link";
  void validate() const;
};

// Writes a simulated run to a rosbag readable by `rosbag info`, `rosbag play` and RViz:
// /clock, <mount>/points (sensor_msgs/PointCloud2), /odom, /ground_truth, /tf (map->odom from
// the navigator, odom->base_link from odometry), /tf_static (sensor mounts), /cmd_vel,
// /global_costmap, /local_costmap (nav_msgs/OccupancyGrid), /global_plan, /local_plan
// (nav_msgs/Path) and /markers. Call record() once per simulation step, after Navigator::tick.
class BagRecorder {
 public:
  BagRecorder(const std::filesystem::path& file, const RobotProfile& robot, BagRecorderParams params = {});
  ~BagRecorder();
  BagRecorder(const BagRecorder&) = delete;
  BagRecorder& operator=(const BagRecorder&) = delete;

  void record(const sim::Simulation& sim, const SensorFrame& frame, const navigation::Navigator& nav, const Twist& cmd);
  void close();
  std::size_t messages() const { return messages_; }

 private:
  template <typename M>
  void write(const std::string& topic, double stamp_s, const M& msg);

  BagRecorderParams params_;
  RobotProfile robot_;
  std::unique_ptr<rosbag::Bag> bag_;
  double next_map_s_ = 0.0, next_local_s_ = 0.0, next_path_s_ = 0.0;
  std::size_t messages_ = 0;
};

struct BagRunSummary {
  navigation::NavStatus status;
  double time_s = 0.0;
  std::size_t messages = 0;
  bool collided = false;
};

// Runs a scenario closed-loop like runner::run_scenario and records every step into `bag_file`
// (the engine of `bipednav_record` and of `bipednav run --bag`).
BagRunSummary run_scenario_to_bag(const sim::Scenario& scenario, const runner::RunOptions& options,
                                  const std::filesystem::path& bag_file, const BagRecorderParams& params = {});

}  // namespace bipednav::ros1
