#include "bipednav/sim/simulation.hpp"

#include <cmath>

#include "bipednav/common/cpu_time.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::sim {
namespace {

// Independent, reproducible streams per sensor from one scenario seed (splitmix64).
std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ull * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

World prepared(World world, bool add_ground) {
  if (add_ground) ensure_ground_plane(world);
  return world;
}

}  // namespace

void SimulationParams::validate() const {
  require(step_s > 0 && step_s <= 0.1 && std::isfinite(step_s), "step_s", "in (0, 0.1] s");
  lidar.validate();
  require(step_s <= 1.0 / lidar.rate_hz, "step_s", "<= one LiDAR sweep period");
  depth.validate();
  odometry.validate();
  raycaster.validate();
  collision.validate();
}

bool ensure_ground_plane(World& world) {
  for (const Geometry& g : world.statics)
    if (const auto* p = std::get_if<Plane>(&g.shape)) {
      const Eigen::Vector3d n = g.T_parent_shape.linear() * p->normal.normalized();
      if (std::abs(n.z()) > 1.0 - 1e-6) return false;
    }
  world.statics.push_back(Geometry{"ground_plane", SE3::Identity(), Plane{}});
  return true;
}

Simulation::Simulation(World world, RobotProfile robot, const Pose2& start, const SimulationParams& params)
    : params_((params.validate(), params)),
      world_(prepared(std::move(world), params.add_ground_plane)),
      caster_(world_, params.raycaster),
      collision_(world_, robot.footprint_radius_m, robot.height_m, params.collision),
      robot_(robot, start),
      clock_(params.step_s),
      odometry_(params.odometry, derive_seed(params.seed, 0)),
      odometry_gate_(params.odometry.rate_hz),
      min_clearance_m_(std::numeric_limits<double>::infinity()) {
  std::uint64_t stream = 1;
  for (const SensorMount& m : robot.sensors) {
    if (m.type == "vlp16" && params.enable_lidar && !lidar_) {
      lidar_mount_ = m;
      lidar_ = std::make_unique<Vlp16>(params.lidar, m.name, derive_seed(params.seed, stream));
    } else if (m.type == "d430" && params.enable_depth) {
      cameras_.push_back(Camera{m, DepthCamera(params.depth, m.name, derive_seed(params.seed, stream))});
    }
    ++stream;
  }
  update_collision();
}

SensorFrame Simulation::step(const Twist& cmd) {
  if (!cmd.is_finite()) throw Error("Simulation::step: non-finite velocity command");
  const double t0 = clock_.now_s();
  const double t1 = static_cast<double>(clock_.ticks() + 1) * clock_.step_s();
  caster_.set_time(t0);
  robot_.step(cmd, t1 - t0);
  auto pose_at = [&](double t) { return se3_from_pose2(robot_.pose_in_last_step(t - t0)); };

  SensorFrame frame;
  frame.stamp_s = t1;
  if (lidar_) {
    const SE3 T_base_lidar = lidar_mount_->T_base_sensor();
    const Stopwatch sw;
    const CpuScope cpu(stats_.lidar_cpu_ms);
    frame.lidar = lidar_->fire_until(t1, caster_, [&](double t) { return pose_at(t) * T_base_lidar; });
    stats_.lidar_ms += sw.elapsed_ms();
    if (frame.lidar) ++stats_.lidar_sweeps;
  }
  for (Camera& c : cameras_) {
    while (c.camera.next_capture_s() < t1) {
      const Stopwatch sw;
      const CpuScope cpu(stats_.depth_cpu_ms);
      const double t = c.camera.next_capture_s();
      if (depth_demand_ && !depth_demand_(c.mount.name, t, t1, c.camera.capture_after_next_s() < t1)) {
        c.camera.skip_capture();
        ++stats_.depth_images_skipped;
        continue;
      }
      frame.depth.push_back(DepthCloud{c.mount.name, c.camera.capture(pose_at(t) * c.mount.T_base_sensor(), caster_)});
      stats_.depth_ms += sw.elapsed_ms();
      ++stats_.depth_images;
    }
  }
  if (params_.enable_odometry) {
    odometry_.integrate(robot_.state().velocity, t1 - t0);
    if (odometry_gate_.ready(t1))
      frame.odometry = odometry_.measure(t1, robot_.state().roll_rad, robot_.state().pitch_rad);
  }
  clock_.advance();
  update_collision();
  ++stats_.steps;
  return frame;
}

void Simulation::recycle(SensorFrame&& frame) {
  if (lidar_ && frame.lidar) lidar_->recycle(std::move(*frame.lidar));
  for (DepthCloud& d : frame.depth)
    for (Camera& c : cameras_)
      if (c.mount.name == d.camera) {
        c.camera.recycle(std::move(d.cloud));
        break;
      }
}

void Simulation::update_collision() {
  const double t = clock_.now_s();
  const bool was_touching = proximity_.clearance_m < 0.0;
  proximity_ = collision_.nearest(robot_.state().pose.position(), t);
  min_clearance_m_ = std::min(min_clearance_m_, proximity_.clearance_m);
  if (proximity_.clearance_m < 0.0 && !was_touching) {
    contacts_.push_back(CollisionEvent{t, robot_.state().pose, proximity_.point, proximity_.obstacle,
                                       -proximity_.clearance_m, robot_.state().velocity});
    if (!first_collision_) first_collision_ = contacts_.back();
  }
}

std::vector<SE3> Simulation::actor_poses() const {
  std::vector<SE3> poses;
  for (const Actor& a : world_.actors) poses.push_back(a.pose_at(now_s()));
  return poses;
}

SE3 Simulation::T_world_sensor(const std::string& mount_name) const {
  const SensorMount* m = robot_.profile().sensor(mount_name);
  if (!m) throw Error("Simulation: robot '" + robot_.profile().name + "' has no sensor '" + mount_name + "'");
  return se3_from_pose2(true_pose()) * m->T_base_sensor();
}

}  // namespace bipednav::sim
