#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/sensor_frame.hpp"
#include "bipednav/sim/collision.hpp"
#include "bipednav/sim/depth_camera.hpp"
#include "bipednav/sim/odometry_model.hpp"
#include "bipednav/sim/raycaster.hpp"
#include "bipednav/sim/robot_model.hpp"
#include "bipednav/sim/vlp16.hpp"
#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

struct SimulationParams {
  double step_s = 0.01;
  std::uint64_t seed = 0;
  bool enable_lidar = true;  // the profile's vlp16 mount (if any)
  bool enable_depth = true;  // every d430 mount of the profile
  bool enable_odometry = true;
  bool add_ground_plane = true;  // adds an unbounded z = 0 plane when the world has no horizontal plane
  Vlp16Params lidar;
  DepthCameraParams depth;
  OdometryParams odometry;
  RayCasterParams raycaster;
  CollisionParams collision;

  void validate() const;
};

// A time the robot's footprint came into contact with an obstacle (the step that began a contact).
struct CollisionEvent {
  double time_s = 0.0;
  Pose2 pose;                   // true robot pose then
  Eigen::Vector2d point{0, 0};  // contact point on the obstacle
  std::string obstacle;         // geometry name
  double penetration_m = 0.0;   // -clearance at detection (>= 0)
  Twist velocity;               // true body velocity then (base frame; a walker's sway in linear_y)
};

// Whether the robot stood still when it was touched (a person walked into it): its forward speed
// and yaw rate at most these. A walker's sway, its gait stepping in place, is not motion.
inline bool robot_standing(const CollisionEvent& e, double max_speed_mps = 0.05, double max_yaw_rate_radps = 0.1) {
  return std::abs(e.velocity.linear_x) <= max_speed_mps && std::abs(e.velocity.angular_z) <= max_yaw_rate_radps;
}

// Cost of the sensors, for benchmarks: wall clock, and process CPU time (see cpu_time.hpp).
struct SimulationStats {
  std::uint64_t steps = 0;
  std::uint64_t lidar_sweeps = 0;
  double lidar_ms = 0.0;  // total time firing LiDAR columns
  std::uint64_t depth_images = 0;
  std::uint64_t depth_images_skipped = 0;  // declined by the depth demand (Simulation::set_depth_demand)
  double depth_ms = 0.0;                   // total time rendering depth images
  double lidar_cpu_ms = 0.0;               // the same two in process CPU time
  double depth_cpu_ms = 0.0;
};

// The built-in simulator on simulated time. Each step(): the actors move to the step's start
// time, the robot model advances by step_s under the command, then every sensor sample whose
// time t falls in [t0, t0 + step_s) is taken from the robot pose at exactly t (LiDAR columns
// one by one, depth images at k / rate, odometry at its rate), and collisions are checked at
// the step's end. Sensor frames are named after the profile's mounts; the base frame is at
// ground level under the robot centre, so T_world_sensor(t) = se3_from_pose2(pose(t)) *
// mount.T_base_sensor(). The robot is not stopped by collisions (there is no physics); each
// contact is recorded once, at the step it began. Same seed and commands -> bit-identical outputs.
class Simulation {
 public:
  Simulation(World world, RobotProfile robot, const Pose2& start, const SimulationParams& params = {});

  // Advances one fixed step; returns the sensor data completed in it (stamp_s = time after the step).
  SensorFrame step(const Twist& cmd);
  // Hands back a frame step() returned (optional): later frames' clouds are written into its
  // clouds' buffers instead of newly allocated ones (the loop would otherwise free and allocate
  // each depth image's 1.2 MB every frame). Outputs do not change.
  void recycle(SensorFrame&& frame);

  // Asked before each depth image is rendered: (camera mount name, capture time, the step's end
  // time = the frame's stamp, whether a later image of the same camera falls in this step). false:
  // the image is neither rendered nor delivered; its noise draws are skipped (DepthCamera::
  // skip_capture), so every later image is the same as without the demand. For a consumer that
  // would drop the image unseen (Navigator::wants_depth), as Gazebo renders a camera only for its
  // subscribers. None (the default): every image is rendered.
  using DepthDemand =
      std::function<bool(const std::string& camera, double capture_s, double frame_stamp_s, bool newer_in_step)>;
  void set_depth_demand(DepthDemand demand) { depth_demand_ = std::move(demand); }

  double now_s() const { return clock_.now_s(); }
  Pose2 true_pose() const { return robot_.state().pose; }
  Twist true_velocity() const { return robot_.state().velocity; }
  const std::optional<CollisionEvent>& first_collision() const { return first_collision_; }
  // Every contact so far, oldest first: one event per step at which the footprint, clear of every
  // obstacle at the step before, penetrates one (a long scrape is one contact).
  const std::vector<CollisionEvent>& contacts() const { return contacts_; }
  bool in_collision() const { return proximity_.clearance_m < 0.0; }
  double clearance_m() const { return proximity_.clearance_m; }  // now
  double min_clearance_m() const { return min_clearance_m_; }    // over the run so far
  const Proximity& nearest_obstacle() const { return proximity_; }
  const World& world() const { return world_; }
  const RobotProfile& robot() const { return robot_.profile(); }
  const SimulationParams& params() const { return params_; }
  std::vector<SE3> actor_poses() const;  // at now_s(), one per world().actors entry
  // True pose of a mounted sensor now (throws Error for an unknown name).
  SE3 T_world_sensor(const std::string& mount_name) const;
  const RayCaster& raycaster() const { return caster_; }
  const SimulationStats& stats() const { return stats_; }

 private:
  struct Camera {
    SensorMount mount;
    DepthCamera camera;
  };
  void update_collision();

  SimulationParams params_;
  World world_;
  RayCaster caster_;
  CollisionChecker collision_;
  RobotModel robot_;
  SimClock clock_;
  std::optional<SensorMount> lidar_mount_;
  std::unique_ptr<Vlp16> lidar_;
  std::vector<Camera> cameras_;
  DepthDemand depth_demand_;
  OdometryModel odometry_;
  RateGate odometry_gate_;
  Proximity proximity_;
  double min_clearance_m_;
  std::optional<CollisionEvent> first_collision_;
  std::vector<CollisionEvent> contacts_;
  SimulationStats stats_;
};

// Adds an unbounded z = 0 plane named "ground_plane" unless `world` already has a horizontal
// plane. Returns true if one was added.
bool ensure_ground_plane(World& world);

}  // namespace bipednav::sim
