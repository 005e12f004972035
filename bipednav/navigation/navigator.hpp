#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/bt/factory.hpp"
#include "bipednav/bt/tree.hpp"
#include "bipednav/bt/xml.hpp"
#include "bipednav/common/sensor_frame.hpp"
#include "bipednav/localization/localizer.hpp"
#include "bipednav/mapping/global_costmap.hpp"
#include "bipednav/mapping/local_costmap.hpp"
#include "bipednav/navigation/navigation_server.hpp"
#include "bipednav/navigation/sensor_gate.hpp"
#include "bipednav/perception/pipeline.hpp"
#include "bipednav/planning/local/moving_obstacle_params.hpp"
#include "bipednav/planning/local/moving_obstacles.hpp"

namespace bipednav::navigation {

// Robot profiles and behavior trees: $BIPEDNAV_CONFIG_DIR, else the source tree's config/.
std::string config_dir();

// The localizer's parameters, a part of the navigator's (the Localizer lives in localization/).
using localization::LocalizerParams;

struct NavigatorParams {
  perception::PerceptionParams perception;
  LocalizerParams localization;
  mapping::LocalCostmapParams local_map;    // 10 Hz
  mapping::GlobalCostmapParams global_map;  // 2 Hz
  ServerParams server;
  double control_rate_hz = 10.0;  // behavior tree, TEB; D* Lite at 5 Hz inside the tree
  SensorGateParams sensors;       // stale / out-of-order / NaN data; SensorsAlive = no range sensor silent
  planning::local::MovingObstacleParams moving_obstacles;  // blob tracking at the local map's rate
  std::string behavior_tree;                               // BT XML file (navigate.xml)
  // The local planner and the moving-obstacle yield limit their accelerations from (and roll out
  // from) the measured velocity, or, with this on, from the last command while it is the slower
  // (acceleration_reference). A walker follows its commands with a lag (0.3 s on Digit), so a
  // command clamped to the measured velocity minus one period's change brakes at about a third of
  // the limit and walks on into a mover's lane. On for Digit (config/digit.params.yaml; docs/closed-loop-log.md,
  // 'Walkers brake from their last command').
  bool brake_from_last_command = false;
  // Each local map update integrates only the newest frame of each depth camera (Nav2's observation
  // buffer with observation_persistence 0), instead of every frame since the last update. A depth
  // frame that the camera's next frame will supersede before the next update is not processed at
  // all: the next frame is expected one camera period (from the stamps of its last two frames)
  // after this one arrived, and the update is the local map gate's next slot. A frame whose
  // successor is late (dropped, delayed) leaves that update without the camera. At 15 Hz cameras
  // and a 10 Hz map one frame in three is skipped (perception and the local map's rays and marks).
  // On for the TurtleBot3 (config/turtlebot3.params.yaml, the fast profile: less perception and local map CPU, screened
  // with its other two switches; alone it lost runs); off here and for walkers. Test NewestDepthOnly.* (evidence:
  // docs/closed-loop-log.md, 'Parameter evidence').
  bool newest_depth_only = false;

  // The defaults with the values that derive from the profile (radii from footprint and sway, velocity
  // limits, TEB's lag model, odometry-jump bounds, obstacle height); the robot's tuning is data
  // (config/<name>.params.yaml, navigator_params_for).
  static NavigatorParams for_robot(const RobotProfile& robot);
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("control_rate_hz", control_rate_hz);
    v("brake_from_last_command", brake_from_last_command);
    v("newest_depth_only", newest_depth_only);
    v("behavior_tree", behavior_tree);
    v.group("local_map", local_map);
    v.group("global_map", global_map);
    v.group("perception", perception);
    v.group("localization", localization);
    v.group("sensors", sensors);
    v.group("moving_obstacles", moving_obstacles);
    v.group("server", server);
  }
};

// The velocity a command's acceleration limits apply from: per component, the last command when
// it is slower than the measured velocity (the robot is still catching up with a slow-down), else
// the measured velocity.
Twist acceleration_reference(const Twist& measured, const Twist& last_command);

// The profile's LiDAR mount name (empty without one) and its depth camera mount names.
std::string lidar_mount_name(const RobotProfile& robot);
std::vector<std::string> depth_mount_names(const RobotProfile& robot);

enum class NavState { IDLE, ACTIVE, SUCCEEDED, FAILED };
const char* nav_state_name(NavState s);

struct NavStatus {
  NavState state = NavState::IDLE;
  Result result;            // the move_base outcome once finished
  std::string active_leaf;  // the behavior tree's running leaf
};

struct NavigatorTimings {
  double perception_ms = 0.0, localization_ms = 0.0, local_map_ms = 0.0, global_map_ms = 0.0, control_ms = 0.0;
};

// Process CPU time per stage summed over every tick so far (cpu_time.hpp). `control` is the
// behavior tree with the planners it runs (D* Lite, TEB) and the moving-obstacle yield.
struct NavigatorCpu {
  // control_ms is the whole control step; global_planner_ms and local_planner_ms are its parts in
  // D* Lite / A* and in TEB / the tracker (not added again by total_ms).
  double sensor_gate_ms = 0.0, localization_ms = 0.0, perception_ms = 0.0, local_map_ms = 0.0, global_map_ms = 0.0,
         control_ms = 0.0, global_planner_ms = 0.0, local_planner_ms = 0.0;
  double total_ms() const {
    return sensor_gate_ms + localization_ms + perception_ms + local_map_ms + global_map_ms + control_ms;
  }
};

// The work space of turning a cloud into observations (navigator.cpp): its runs of points of one
// source, and points per source. Kept between frames by the Navigator.
struct SourceRuns {
  struct Run {
    std::size_t begin, end, k;
  };
  std::vector<Run> runs;
  std::vector<std::size_t> fill;
};

// The navigation pipeline (docs/architecture.md, section 2). Each tick reads one step of sensor data and runs
// perceive -> localize -> map -> plan -> control, every stage at its own rate on the frames'
// clock. Planning and control are driven by the behavior tree (move_base) through the
// NavigationServer's get_path / exe_path / recovery actions.
class Navigator {
 public:
  Navigator(NavigatorParams params, RobotProfile robot, const mapping::GridGeometry& global_geometry,
            const Pose2& initial_pose);
  // Its stages hold references to each other (the server to the maps and the tracker, the tree's
  // leaves to the server): not copied or moved.
  Navigator(const Navigator&) = delete;
  Navigator& operator=(const Navigator&) = delete;

  // One step: returns the velocity command for the walking controller (zero when idle/stopped).
  Twist tick(const SensorFrame& frame);
  // move_base: a new goal (preempts the running one).
  void set_goal(const Pose2& goal);
  void cancel();

  const NavStatus& status() const { return status_; }
  Pose2 pose() const { return localizer_.T_map_base(); }
  Pose2 T_map_odom() const { return localizer_.T_map_odom(); }
  const mapping::LocalCostmap& local_map() const { return local_; }
  const mapping::GlobalCostmap& global_map() const { return global_; }
  const Path& global_path() const { return global_path_; }
  // Counts the changes of global_path(): equal versions mean the same path.
  std::uint64_t global_path_version() const { return global_path_version_; }
  const Path& local_trajectory() const { return server_.local_trajectory(); }
  const perception::PerceptionOutput& last_perception() const { return perception_out_; }
  const std::optional<Pose2>& goal() const { return goal_; }
  std::size_t replans() const { return server_.plans(); }
  std::size_t recoveries() const { return server_.recoveries(); }
  const std::vector<RecoveryRecord>& recovery_log() const { return server_.recovery_log(); }
  const NavigatorTimings& timings() const { return timings_; }  // wall time of the last run of each stage
  const NavigatorCpu& cpu() const { return cpu_; }
  const bt::BehaviorTree& tree() const { return tree_; }
  const NavigationServer& server() const { return server_; }
  const SensorGate& sensor_gate() const { return gate_; }
  const RobotProfile& robot() const { return robot_; }
  const planning::local::MovingObstacleTracker& moving_obstacles() const { return moving_; }
  // The obstacle points (map frame) and their heights above the floor that the latest local map
  // update marked (the moving-obstacle tracker's input; empty while it is disabled), and that
  // update's time.
  const std::vector<Eigen::Vector2d>& obstacle_points() const { return moving_points_; }
  const std::vector<double>& obstacle_heights() const { return moving_heights_; }
  double obstacle_points_stamp_s() const { return moving_points_stamp_s_; }
  // Depth frames not processed under NavigatorParams::newest_depth_only (superseded before the
  // local map would have integrated them).
  std::size_t depth_frames_skipped() const { return depth_frames_skipped_; }
  // newest_depth_only ahead of the sensor (a sim::Simulation::DepthDemand): whether the image of
  // `camera` captured at capture_s, to arrive in the frame stamped frame_stamp_s (the next tick's),
  // would be processed; false counts it as skipped. The same decision tick() makes for a
  // delivered image, taken before the image exists, so a simulator need not render the images
  // the navigator would drop. Once called, tick() takes the depth images it gets as already
  // judged (an image the camera never delivers cannot be judged in tick()). Without
  // newest_depth_only every image is wanted. Only for frames delivered in the step they are
  // captured in (no injected delays): the decision uses the map gate's state at that step.
  bool wants_depth(const std::string& camera, double capture_s, double frame_stamp_s, bool newer_in_step);

 private:
  void perceive(const perception::PerceptionInput& in);
  void update_maps();
  void track_moving_obstacles();
  Twist yield_to_moving_obstacles(const Twist& cmd) const;
  Twist reference_velocity() const;  // see NavigatorParams::brake_from_last_command
  void control();
  void register_leaves(bt::Factory& factory);
  bt::Factory leaf_factory();  // the engine's nodes and this navigator's leaves
  bool sensors_alive() const;
  void finish(bt::Status status);
  std::string weak_estimate_note() const;  // empty unless the position estimate is weak at the goal
  bool depth_superseded(const SensorFrame& frame, const Admission& admitted, std::size_t i);
  bool depth_superseded(const std::string& camera, double stamp_s, double now_s, bool newer_in_step);

  NavigatorParams params_;
  RobotProfile robot_;
  perception::PerceptionPipeline perception_;
  localization::Localizer localizer_;
  SensorGate gate_;
  mapping::LocalCostmap local_;
  mapping::GlobalCostmap global_;
  planning::local::MovingObstacleTracker moving_;  // the local planner reads it too
  NavigationServer server_;
  bt::BehaviorTree tree_;
  RateGate local_gate_, global_gate_, control_gate_;
  perception::PerceptionOutput perception_out_;
  perception::PerceptionInput perception_in_;  // this tick's admitted clouds (buffer kept between ticks)
  std::vector<mapping::Observation> local_obs_, lidar_obs_;
  std::vector<std::vector<Eigen::Vector3f>> spare_points_;  // point buffers of used observations, for reuse
  SourceRuns source_runs_;
  std::vector<Eigen::Vector2d> moving_points_;  // track_moving_obstacles' input, kept for reuse
  std::vector<double> moving_heights_;
  double moving_points_stamp_s_ = -1.0;
  struct DepthClock {
    std::string camera;
    double last_stamp_s = 0.0;
  };
  std::vector<DepthClock> depth_clocks_;  // newest_depth_only: each camera's last frame stamp
  std::size_t depth_frames_skipped_ = 0;
  bool depth_judged_ahead_ = false;  // wants_depth has been called: tick() keeps every depth image
  std::optional<Pose2> goal_;
  Path global_path_;
  std::uint64_t global_path_version_ = 0;
  NavStatus status_;
  NavigatorTimings timings_;
  NavigatorCpu cpu_;
  Twist cmd_;
  double now_s_ = 0.0;
  std::string lidar_name_;  // the profile's vlp16 mount
  Result last_failure_;     // the last failure a leaf reported (with its error_code)
  bool map_ready_ = false;  // the global map has seen a LiDAR sweep (or the first seconds passed)
};

}  // namespace bipednav::navigation
