// bipednav_sim_node: the built-in simulator as a ROS 1 node. It owns the clock: each step of
// step_s simulated seconds it publishes /clock, then the sensor data completed in the step, and
// it paces the steps on the wall clock at `real_time_factor` (x1 by default; 0 = as fast as
// possible, only sensible when the consumers keep up). cmd_vel is read between steps.
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <csignal>
#include <map>
#include <memory>

#include "bipednav/control/gait_command.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/simulation.hpp"
#include "ros/conversions.hpp"
#include "ros/map_params.hpp"

namespace bipednav::ros1 {
namespace {

struct SimNodeParams {
  std::string scenario;
  std::string robot;       // empty: the scenario's
  std::string config_dir;  // empty: the compiled-in config/
  std::string odom_frame = "odom", base_frame = "base_link", world_frame = "map";
  double real_time_factor = 1.0;
  double cmd_timeout_s = 0.5;  // stop the robot when cmd_vel goes silent (simulated seconds)
  int seed = -1;               // < 0: the scenario's
};

// Set by SIGINT and SIGTERM: the node leaves its loop and removes its ~map_area before it shuts
// down, so that no navigation node started later sizes its map from a scenario that has ended.
volatile std::sig_atomic_t g_stop = 0;
void request_stop(int) { g_stop = 1; }

class SimNode {
 public:
  SimNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  void run();

 private:
  void publish(const SensorFrame& frame);

  SimNodeParams p_;
  sim::Scenario scenario_;
  std::unique_ptr<sim::Simulation> sim_;
  // cmd_vel goes to the simulated walking controller through a watchdog: non-finite commands
  // become zero, and silence longer than cmd_timeout_s stops the robot.
  control::GaitCommandBuffer gait_;
  std::unique_ptr<control::StopOnSilence> watchdog_;
  ros::Publisher clock_pub_, odom_pub_, truth_pub_;
  std::map<std::string, ros::Publisher> cloud_pubs_;
  ros::Subscriber cmd_sub_;
  tf2_ros::TransformBroadcaster tf_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
};

SimNode::SimNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  pnh.param("scenario", p_.scenario, p_.scenario);
  pnh.param("robot", p_.robot, p_.robot);
  pnh.param("config_dir", p_.config_dir, p_.config_dir);
  pnh.param("odom_frame", p_.odom_frame, p_.odom_frame);
  pnh.param("base_frame", p_.base_frame, p_.base_frame);
  pnh.param("world_frame", p_.world_frame, p_.world_frame);
  pnh.param("real_time_factor", p_.real_time_factor, p_.real_time_factor);
  pnh.param("cmd_timeout_s", p_.cmd_timeout_s, p_.cmd_timeout_s);
  pnh.param("seed", p_.seed, p_.seed);
  if (p_.scenario.empty()) throw Error("bipednav_sim_node: parameter ~scenario (a scenario YAML file) is required");
  require(p_.real_time_factor >= 0.0, "real_time_factor", ">= 0");
  watchdog_ = std::make_unique<control::StopOnSilence>(gait_, control::StopOnSilenceParams{p_.cmd_timeout_s});
  scenario_ = sim::load_scenario(p_.scenario);
  const RobotProfile robot = navigation::load_robot(p_.robot.empty() ? scenario_.robot : p_.robot, p_.config_dir);
  sim::SimulationParams sp;
  sp.seed = p_.seed >= 0 ? static_cast<std::uint64_t>(p_.seed) : scenario_.seed;
  sim_ = std::make_unique<sim::Simulation>(scenario_.world, robot, scenario_.start, sp);
  // The scenario's map area and start for the navigation node (its ~map_area_param names this), which
  // then sizes its global map as a closed-loop run does (runner::global_geometry_for).
  MapParams map;
  map.area = runner::map_area_for(scenario_);
  map.initial = scenario_.start;
  pnh.setParam("map_area", to_param(map));
  clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10);
  odom_pub_ = nh.advertise<nav_msgs::Odometry>("odom", 50);
  truth_pub_ = nh.advertise<nav_msgs::Odometry>("ground_truth", 10);
  std::vector<geometry_msgs::TransformStamped> mounts;
  for (const auto& m : robot.sensors) {
    cloud_pubs_[m.name] = nh.advertise<sensor_msgs::PointCloud2>(m.name + "/points", 4);
    mounts.push_back(to_transform(m.T_base_sensor(), p_.base_frame, m.name, 0.0));
  }
  static_tf_.sendTransform(mounts);
  cmd_sub_ = nh.subscribe<geometry_msgs::Twist>("cmd_vel", 10, [this](const geometry_msgs::Twist::ConstPtr& msg) {
    watchdog_->send(from_msg(*msg), sim_->now_s());
  });
  ROS_INFO("bipednav_sim_node: scenario %s, robot %s, step %.3f s, real-time factor %.2f", scenario_.name.c_str(),
           robot.name.c_str(), sp.step_s, p_.real_time_factor);
}

void SimNode::publish(const SensorFrame& frame) {
  rosgraph_msgs::Clock clock;
  clock.clock = to_time(frame.stamp_s);
  clock_pub_.publish(clock);
  if (frame.odometry) {
    odom_pub_.publish(to_msg(*frame.odometry, p_.odom_frame, p_.base_frame));
    tf_.sendTransform(to_transform(frame.odometry->T_odom_base, p_.odom_frame, p_.base_frame, frame.odometry->stamp_s));
    Odometry truth;
    truth.stamp_s = frame.stamp_s;
    truth.T_odom_base = sim_->true_pose();
    truth.velocity = sim_->true_velocity();
    truth_pub_.publish(to_msg(truth, p_.world_frame, p_.base_frame + "_truth"));
  }
  if (frame.lidar) cloud_pubs_[frame.lidar->frame_id].publish(to_msg(*frame.lidar));
  for (const auto& d : frame.depth) {
    auto msg = to_msg(d.cloud);
    msg.header.frame_id = d.camera;
    cloud_pubs_[d.camera].publish(msg);
  }
}

void SimNode::run() {
  const double step_s = sim_->params().step_s;
  const bool paced = p_.real_time_factor > 0.0;
  ros::WallRate rate(paced ? p_.real_time_factor / step_s : 1000.0);
  rosgraph_msgs::Clock clock;  // t = 0 first, so use_sim_time nodes start
  clock_pub_.publish(clock);
  while (ros::ok() && !g_stop) {
    ros::spinOnce();
    watchdog_->tick(sim_->now_s());
    SensorFrame frame = sim_->step(gait_.last());
    publish(frame);
    sim_->recycle(std::move(frame));  // its clouds' buffers hold the next frames' clouds
    if (sim_->first_collision() && sim_->first_collision()->time_s + step_s >= sim_->now_s())
      ROS_WARN("bipednav_sim_node: collision with %s at t = %.2f s", sim_->first_collision()->obstacle.c_str(),
               sim_->first_collision()->time_s);
    if (paced) rate.sleep();
  }
}

}  // namespace
}  // namespace bipednav::ros1

int main(int argc, char** argv) {
  ros::init(argc, argv, "bipednav_sim_node", ros::init_options::NoSigintHandler);
  ros::NodeHandle nh, pnh("~");
  std::signal(SIGINT, bipednav::ros1::request_stop);
  std::signal(SIGTERM, bipednav::ros1::request_stop);
  int status = 0;
  try {
    bipednav::ros1::SimNode node(nh, pnh);
    node.run();
  } catch (const std::exception& e) {
    ROS_FATAL("bipednav_sim_node: %s", e.what());
    status = 1;
  }
  pnh.deleteParam("map_area");
  ros::shutdown();
  return status;
}
