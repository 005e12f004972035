// bipednav_nav_node: the Navigator as a ROS 1 node. Callbacks only convert messages, call the
// core and publish; all conversion is in conversions.cpp. See ros/README.md for topics/params.
#include <actionlib/server/simple_action_server.h>
#include <move_base_msgs/MoveBaseAction.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <cstdio>
#include <map>
#include <memory>
#include <optional>

#include "bipednav/navigation/map_area.hpp"
#include "bipednav/navigation/navigator.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "ros/conversions.hpp"
#include "ros/map_params.hpp"

namespace bipednav::ros1 {
namespace {

struct NodeParams {
  std::string robot = "turtlebot3";
  std::string config_dir;  // empty: the compiled-in config/
  // A dictionary parameter holding the map parameters (the simulator node's ~map_area for its
  // scenario, e.g. /bipednav_sim/map_area), waited for up to map_area_wait_s of wall time since the
  // nodes start together; the single map parameters win over it. Empty: those alone.
  std::string map_area_param;
  double map_area_wait_s = 30.0;
  std::string map_frame = "map", odom_frame = "odom", base_frame = "base_link";
  double tick_rate_hz = 50.0;
  MapParams map;                   // the global map's area and the initial pose
  double footstep_length_m = 0.0;  // > 0 draws footstep markers (walkers)
};

// A fixed-rate gate on the ROS clock for publishing.
struct Every {
  double period_s;
  double next_s = 0.0;
  bool ready(double now) {
    if (now + 1e-9 < next_s) return false;
    next_s = now + period_s;
    return true;
  }
};

class NavNode {
 public:
  NavNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);

 private:
  void load(ros::NodeHandle& pnh);
  void on_goal();
  void on_preempt();
  void on_simple_goal(const geometry_msgs::PoseStamped& msg);
  std::optional<Pose2> goal_in_map(const geometry_msgs::PoseStamped& msg);
  void on_tick(const ros::TimerEvent&);
  void report_action();
  void publish(double now);

  NodeParams p_;
  RobotProfile robot_;
  navigation::NavigatorParams nav_params_;
  mapping::GridGeometry geometry_;
  Pose2 initial_;
  std::unique_ptr<navigation::Navigator> nav_;
  SensorFrame pending_;
  ros::Publisher cmd_pub_, global_map_pub_, local_map_pub_, plan_pub_, traj_pub_, marker_pub_;
  std::vector<ros::Subscriber> subs_;
  ros::Timer timer_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_{tf_buffer_};
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  actionlib::SimpleActionServer<move_base_msgs::MoveBaseAction> server_;
  double last_tf_s_ = -1.0;
  Every global_gate_{0.5}, local_gate_{0.2}, path_gate_{0.2}, feedback_gate_{0.2};
};

template <typename T>
T param(ros::NodeHandle& pnh, const std::string& name, T def) {
  pnh.param<T>(name, def, def);
  return def;
}

// The value of the dictionary parameter `name`, once some node has set it (within wait_s of wall time).
std::map<std::string, double> published_param(const std::string& name, double wait_s) {
  std::map<std::string, double> values;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(wait_s);
  while (!ros::param::get(name, values)) {
    if (!ros::ok() || ros::WallTime::now() > deadline) {
      char waited[32];
      std::snprintf(waited, sizeof waited, "%g s", wait_s);
      throw Error("parameter " + name + " (~map_area_param) not set within " + waited +
                  ": is the simulator node running? (or give the map parameters ~map_min_x_m ...)");
    }
    ros::WallDuration(0.1).sleep();
  }
  return values;
}

void NavNode::load(ros::NodeHandle& pnh) {
  if (pnh.hasParam("scenario"))
    throw Error(
        "~scenario: the navigation node reads no scenario files; set ~map_area_param (the simulator node "
        "publishes its scenario's map area as /bipednav_sim/map_area) or ~map_min_x_m .. ~map_max_y_m");
  p_.robot = param(pnh, "robot", p_.robot);
  p_.config_dir = param(pnh, "config_dir", p_.config_dir);
  p_.map_area_param = param(pnh, "map_area_param", p_.map_area_param);
  p_.map_area_wait_s = param(pnh, "map_area_wait_s", p_.map_area_wait_s);
  p_.map_frame = param(pnh, "map_frame", p_.map_frame);
  p_.odom_frame = param(pnh, "odom_frame", p_.odom_frame);
  p_.base_frame = param(pnh, "base_frame", p_.base_frame);
  p_.tick_rate_hz = param(pnh, "tick_rate_hz", p_.tick_rate_hz);
  p_.footstep_length_m = param(pnh, "footstep_length_m", p_.footstep_length_m);
  robot_ = navigation::load_robot(p_.robot, p_.config_dir);
  // The robot's defaults, then a navigation parameters file (`bipednav params --robot R` prints
  // one); the single ROS params below still override it.
  nav_params_ = navigation::navigator_params_for(robot_, param(pnh, "params_file", std::string()), p_.config_dir);
  auto& n = nav_params_;
  n.server.global_planner = param(pnh, "global_planner", n.server.global_planner);
  n.server.local_planner = param(pnh, "local_planner", n.server.local_planner);
  n.localization.method = param(pnh, "localization", n.localization.method);
  n.server.goal.xy_tolerance_m = param(pnh, "goal_xy_tolerance_m", n.server.goal.xy_tolerance_m);
  n.server.goal.yaw_tolerance_rad = param(pnh, "goal_yaw_tolerance_rad", n.server.goal.yaw_tolerance_rad);
  n.global_map.resolution_m = param(pnh, "global_resolution_m", n.global_map.resolution_m);
  n.control_rate_hz = param(pnh, "control_rate_hz", n.control_rate_hz);
  n.behavior_tree = param(pnh, "behavior_tree", n.behavior_tree);
  n.validate();
  require(p_.tick_rate_hz > 0.0, "tick_rate_hz", "> 0");
  require(p_.map_area_wait_s >= 0.0, "map_area_wait_s", ">= 0");
  if (!p_.map_area_param.empty())
    apply_param(published_param(p_.map_area_param, p_.map_area_wait_s), p_.map_area_param, p_.map);
  p_.map.fields([&](const char* name, double& v) { v = param(pnh, name, v); });
  geometry_ = navigation::global_grid_for(p_.map.area, n.global_map.resolution_m);
  initial_ = p_.map.initial;
}

NavNode::NavNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) : server_(nh, "move_base", false) {
  load(pnh);
  nav_ = std::make_unique<navigation::Navigator>(nav_params_, robot_, geometry_, initial_);
  cmd_pub_ = nh.advertise<geometry_msgs::Twist>("cmd_vel", 10);
  global_map_pub_ = nh.advertise<nav_msgs::OccupancyGrid>("global_costmap", 1, true);
  local_map_pub_ = nh.advertise<nav_msgs::OccupancyGrid>("local_costmap", 1);
  plan_pub_ = nh.advertise<nav_msgs::Path>("global_plan", 1, true);
  traj_pub_ = nh.advertise<nav_msgs::Path>("local_plan", 1);
  marker_pub_ = nh.advertise<visualization_msgs::MarkerArray>("markers", 1);
  // One PointCloud2 topic per sensor mount of the robot profile: <mount>/points.
  for (const auto& mount : robot_.sensors) {
    const std::string name = mount.name;
    const bool lidar = mount.type == "vlp16";
    subs_.push_back(nh.subscribe<sensor_msgs::PointCloud2>(
        name + "/points", 4, [this, name, lidar](const sensor_msgs::PointCloud2::ConstPtr& msg) {
          try {
            PointCloud cloud = from_msg(*msg);
            if (lidar) {
              pending_.lidar = std::move(cloud);
            } else {
              pending_.depth.push_back(DepthCloud{name, std::move(cloud)});
            }
          } catch (const std::exception& e) {
            ROS_WARN_THROTTLE(5.0, "bipednav_nav_node: dropped %s cloud: %s", name.c_str(), e.what());
          }
        }));
  }
  subs_.push_back(nh.subscribe<nav_msgs::Odometry>(
      "odom", 20, [this](const nav_msgs::Odometry::ConstPtr& msg) { pending_.odometry = from_msg(*msg); }));
  subs_.push_back(nh.subscribe("move_base_simple/goal", 1, &NavNode::on_simple_goal, this));
  server_.registerGoalCallback([this] { on_goal(); });
  server_.registerPreemptCallback([this] { on_preempt(); });
  server_.start();
  timer_ = nh.createTimer(ros::Duration(1.0 / p_.tick_rate_hz), &NavNode::on_tick, this);
  ROS_INFO("bipednav_nav_node: robot %s, global map %dx%d at %.2f m, planners %s/%s", robot_.name.c_str(),
           geometry_.width, geometry_.height, geometry_.resolution_m, nav_params_.server.global_planner.c_str(),
           nav_params_.server.local_planner.c_str());
}

std::optional<Pose2> NavNode::goal_in_map(const geometry_msgs::PoseStamped& msg) {
  try {
    const Pose2 goal = from_msg(msg.pose);
    const std::string& frame = msg.header.frame_id;
    if (frame.empty() || frame == p_.map_frame) return goal;
    if (frame == p_.odom_frame) return nav_->T_map_odom() * goal;
    const auto T = tf_buffer_.lookupTransform(p_.map_frame, frame, ros::Time(0), ros::Duration(0.2));
    geometry_msgs::Pose origin;
    origin.position.x = T.transform.translation.x;
    origin.position.y = T.transform.translation.y;
    origin.orientation = T.transform.rotation;
    return from_msg(origin) * goal;
  } catch (const std::exception& e) {
    ROS_ERROR("bipednav_nav_node: rejected goal in frame '%s': %s", msg.header.frame_id.c_str(), e.what());
    return std::nullopt;
  }
}

void NavNode::on_goal() {
  const auto goal = server_.acceptNewGoal();  // preempts (PREEMPTED) a running goal
  const auto pose = goal_in_map(goal->target_pose);
  if (!pose) {
    move_base_msgs::MoveBaseResult result;
    server_.setAborted(result, "INVALID_GOAL (53): goal pose could not be transformed into the map frame");
    return;
  }
  ROS_INFO("bipednav_nav_node: new goal (%.2f, %.2f, %.2f)", pose->x, pose->y, pose->theta);
  nav_->set_goal(*pose);
}

void NavNode::on_preempt() {
  // A new goal also raises the preempt request; on_goal() follows and preempts through
  // acceptNewGoal() while the navigator switches goals without stopping.
  if (server_.isNewGoalAvailable()) return;
  nav_->cancel();
  server_.setPreempted(move_base_msgs::MoveBaseResult(), "CANCELED (101): goal canceled by the client");
}

void NavNode::on_simple_goal(const geometry_msgs::PoseStamped& msg) {
  const auto pose = goal_in_map(msg);
  if (!pose) return;
  if (server_.isActive())
    server_.setPreempted(move_base_msgs::MoveBaseResult(), "preempted by a goal on move_base_simple/goal");
  nav_->set_goal(*pose);
}

void NavNode::report_action() {
  if (!server_.isActive()) return;
  const auto& st = nav_->status();
  if (st.state == navigation::NavState::ACTIVE || st.state == navigation::NavState::IDLE) return;
  const std::string text = std::string(outcome_name(st.result.outcome)) + " (" +
                           std::to_string(code(st.result.outcome)) + "): " + st.result.message;
  if (st.state == navigation::NavState::SUCCEEDED) {
    server_.setSucceeded(move_base_msgs::MoveBaseResult(), text);
  } else {
    ROS_WARN("bipednav_nav_node: goal aborted: %s", text.c_str());
    server_.setAborted(move_base_msgs::MoveBaseResult(), text);
  }
}

void NavNode::on_tick(const ros::TimerEvent&) {
  const double now = ros::Time::now().toSec();
  pending_.stamp_s = now;
  Twist cmd;
  try {
    cmd = nav_->tick(pending_);
  } catch (const std::exception& e) {
    ROS_ERROR_THROTTLE(2.0, "bipednav_nav_node: tick failed: %s", e.what());
  }
  pending_ = SensorFrame{};
  cmd_pub_.publish(to_msg(cmd));
  if (now > last_tf_s_) {  // one map -> odom per stamp (tf2 rejects repeated stamps)
    tf_broadcaster_.sendTransform(to_transform(nav_->T_map_odom(), p_.map_frame, p_.odom_frame, now));
    last_tf_s_ = now;
  }
  report_action();
  publish(now);
}

void NavNode::publish(double now) {
  if (global_gate_.ready(now)) global_map_pub_.publish(to_msg(nav_->global_map().costmap(), p_.map_frame, now));
  if (local_gate_.ready(now)) {
    local_map_pub_.publish(to_msg(nav_->local_map().costmap(), p_.map_frame, now));
    MarkerInput m;
    m.frame_id = p_.map_frame;
    m.stamp_s = now;
    m.robot = nav_->pose();
    m.footprint_radius_m = robot_.footprint_radius_m;
    m.goal = nav_->goal();
    m.local_costmap = &nav_->local_map().costmap();
    m.local_trajectory = &nav_->local_trajectory();
    m.step_length_m = p_.footstep_length_m;
    marker_pub_.publish(to_markers(m));
  }
  if (path_gate_.ready(now)) {
    plan_pub_.publish(to_msg(nav_->global_path(), now));
    traj_pub_.publish(to_msg(nav_->local_trajectory(), now));
  }
  if (server_.isActive() && feedback_gate_.ready(now)) {
    move_base_msgs::MoveBaseFeedback fb;
    fb.base_position = to_pose_stamped(nav_->pose(), p_.map_frame, now);
    server_.publishFeedback(fb);
  }
}

}  // namespace
}  // namespace bipednav::ros1

int main(int argc, char** argv) {
  ros::init(argc, argv, "bipednav_nav_node");
  ros::NodeHandle nh, pnh("~");
  try {
    bipednav::ros1::NavNode node(nh, pnh);
    ros::spin();
  } catch (const std::exception& e) {
    ROS_FATAL("bipednav_nav_node: %s", e.what());
    return 1;
  }
  return 0;
}
