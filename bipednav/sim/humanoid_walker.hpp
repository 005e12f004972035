#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "bipednav/common/biped.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/mapping/heightmap.hpp"

namespace bipednav::sim {

// A Nao-sized humanoid that walks by footsteps in the simulator (second reference, section VI).
struct HumanoidWalkerParams {
  BodyModel body;                         // the body the whole-body check sweeps (the planner's model)
  double landing_noise_xy_m = 0.003;      // execution noise of the swing foot's landing (sigma)
  double landing_noise_yaw_rad = 0.01;    // ... of its heading (sigma)
  double odometry_noise_xy_m = 0.002;     // kinematic odometry error per step (sigma)
  double odometry_noise_yaw_rad = 0.005;  // ... per step (sigma)
  double collision_tolerance_m = 0.005;   // penetrations up to this depth are contact, not collision
  double min_support_ratio = 0.7;         // a landed sole less supported than this falls (a collision)
  double support_band_m = 0.015;          // cells this close below the sole's top support it
  double sole_edge_tolerance_m = 0.01;    // a sole overhanging an edge by less than this stands
  int samples_per_segment = 8;            // swing trajectory samples per horizontal segment

  void validate() const;
};

// A step command relative to the stance foot: where the swing foot should land, in the stance
// sole's frame (the walking controller's interface), how long the step takes and how high the
// swing foot is lifted above the stance sole (the planner's swept volume, inverse_heightmap.cpp).
struct StepCommand {
  Pose2 landing_in_stance;
  double duration_s = 0.5;
  double peak_m = 0.04;
  std::string action;
};

// A body part meeting the world during a step (ground truth).
struct BodyContact {
  double time_s = 0.0;
  std::string part;  // swing_foot, landing_foot, torso, left_arm, right_arm
  Eigen::Vector2d point{0, 0};
  double penetration_m = 0.0;
};

struct StepExecution {
  Footstep landed;                    // true pose of the landed foot, z from the terrain
  std::vector<BodyContact> contacts;  // deeper than collision_tolerance_m
  double min_clearance_m = 0.0;       // lowest gap between a swinging/moving part and the terrain
  double landing_spread_m = 0.0;      // max - min terrain height under the landed sole
  double support_ratio = 1.0;         // fraction of the landed sole resting on its top surface
};

// An oriented box footprint with its bottom height, for the ground-truth body check.
struct BodyPart {
  std::string name;
  Pose2 pose;
  double length_m = 0.0, width_m = 0.0, bottom_m = 0.0;
};

// The body parts between two feet at one instant: torso and arms centred between the feet with
// the mean heading, their bottoms above `support_z_m` (the stance sole), as in the planner's
// body model (footstep/inverse_heightmap.cpp).
std::vector<BodyPart> upper_body_parts(const BodyModel& body, const Pose2& a, const Pose2& b, double support_z_m);
// The body pose midway between two feet (mean heading).
Pose2 body_between(const Pose2& a, const Pose2& b);
// Height gap between a part's bottom and the highest terrain under it (+inf over unknown terrain).
double part_clearance_m(const mapping::Heightmap& truth, const BodyPart& part);

// Executes footsteps on the true terrain (a heightmap of the world, `truth`): the swing foot
// rises at its old place, moves at the lifted height to the via point beside the stance foot and
// on to the landing pose (plus noise), and drops onto the terrain there (z = highest terrain
// under the sole); the body stays between the feet. Every part is checked against `truth` along
// the way. Also produces the kinematic odometry of the feet: the executed step relative to the
// stance foot with per-step noise, accumulated.
class HumanoidWalker {
 public:
  HumanoidWalker(const HumanoidWalkerParams& params, const mapping::Heightmap& truth, const Pose2& start_body,
                 std::uint64_t seed);

  // Moves the swing foot (the one that is not the stance foot) and makes it the new stance foot.
  StepExecution step(const StepCommand& command);

  const Footstep& stance() const { return feet_[static_cast<int>(stance_)]; }
  const Footstep& swing() const { return feet_[1 - static_cast<int>(stance_)]; }
  const Footstep& odom_stance() const { return odom_[static_cast<int>(stance_)]; }
  const Footstep& odom_swing() const { return odom_[1 - static_cast<int>(stance_)]; }
  Pose2 body_pose() const { return body_between(feet_[0].pose, feet_[1].pose); }
  // The base frame: between the feet at the stance sole's height, yawed like the body.
  SE3 T_world_base() const { return se3_from_pose2(body_pose(), stance().z_m); }
  SE3 T_odom_base() const;
  double time_s() const { return time_s_; }
  const HumanoidWalkerParams& params() const { return params_; }

 private:
  double sole_height(const Pose2& sole, double* spread, double* support = nullptr) const;
  struct Segment {
    Pose2 from, to;
    double sole_z_m, support_z_m;
  };
  void sweep(const Segment& seg, const Pose2& fixed, double t0, double dt, StepExecution& out) const;

  HumanoidWalkerParams params_;
  const mapping::Heightmap& truth_;
  Rng rng_;
  Footstep feet_[2];
  Footstep odom_[2];
  Foot stance_ = Foot::kLeft;
  double last_peak_m_ = 0.04;
  double time_s_ = 0.0;
};

}  // namespace bipednav::sim
