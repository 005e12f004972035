#pragma once

#include <Eigen/Core>
#include <limits>
#include <span>
#include <string>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/common/velocity_limits.hpp"
#include "bipednav/tracking/tracker.hpp"

namespace bipednav::control {

// The last check between the planner's command and the body, in the manner of Nav2's
// collision_monitor with its approach model: it predicts the body under the command and slows the
// command along the same arc until the prediction is free.
//
// Principle. A command is admissible when the body, following it for one control period, then
// commanded to stop (braking through the same first-order lag and acceleration limits as the
// simulator's body, common/body_response.hpp) and then standing still for standstill_s,
//  - while it moves, never comes within footprint radius + point_margin_m of a raw obstacle
//    point where its distance to that point decreases (a point already inside the footprint does
//    not block moving away from it, nor turning in place), and
//  - at no time, standing still included, comes within footprint radius + mover radius +
//    mover_margin_m + sigma_scale * sigma(t) of a mover's predicted position at the same absolute
//    time (sigma(t): square root of the largest eigenvalue of the predicted position covariance).
// So the robot never stops inside a mover's predicted lane: it stops before entering it and goes
// on once the prediction has passed.
//
// Decision. The output is the largest admissible scale s of the command on the grid
// {1, 1 - 1/scale_steps, ..., 0}, scaling the linear and angular velocities together (the same
// arc, slower), then limited by the acceleration limits from the measured velocity
// (limit_velocity) for speeding up only: a command nearer zero than the limiter allows is passed,
// as the body's own acceleration limits brake it and the prediction assumes so. The prediction
// follows exactly the command sent. When even stopping now (s = 0) is not admissible:
//  - braking cannot stop short of a point: the stop is sent (kStop), as Nav2 would;
//  - a mover reaches the robot where it stops: a few evasive commands (backwards, backward arcs,
//    turns in place, forward straight and arcs, sideways when the limits allow lateral motion),
//    each held over the same horizon under the same body model, are compared with standing and the
//    one hit latest is sent (kEvade; ties: fewer steps in contact, then the larger minimum
//    clearance).
//
// Movers between predicted states are interpolated linearly by absolute time; before the first
// state a mover is extrapolated back with its velocity and the first covariance, after the last
// with its velocity and the covariance growing on at the rate of the last interval (held when
// there is one state only).
struct CollisionMonitorParams {
  bool enabled = true;           // false: commands pass unchanged (non-finite input still stops)
  double point_margin_m = 0.05;  // clearance kept from raw obstacle points beyond the footprint (m)
  double mover_margin_m = 0.10;  // clearance kept from a mover's disc beyond the footprint (m)
  double sigma_scale = 2.0;      // standard deviations of a mover's predicted position added to its radius
  double standstill_s = 2.5;     // time the robot must be able to stand still after stopping (s)
  double sim_step_s = 0.05;      // step of the prediction and of its checks (s)
  int scale_steps = 10;          // the command's scale is searched on 1, 1 - 1/scale_steps, ..., 0

  // Throws ParamError for non-finite or negative values, sim_step_s <= 0 or scale_steps < 1.
  void validate() const;
};

// One control cycle's input. Points and movers are in the map frame, velocities in the base frame.
struct MonitorInput {
  Twist cmd;                                          // the planner's command
  Pose2 pose;                                         // T_map_base
  Twist velocity;                                     // measured body velocity
  std::span<const Eigen::Vector2d> points;            // obstacle points of the latest sensor cycle, no ground
  std::span<const tracking::TrackPrediction> movers;  // MultiObjectTracker::predictions()
  double now_s = 0.0;                                 // absolute time, the movers' clock
  double period_s = 0.1;                              // control period: how long the command is followed
};

struct MonitorDecision {
  enum class Action { kPass, kSlow, kStop, kEvade };

  Twist cmd;           // the command to send
  double scale = 1.0;  // of the planner's command (0 when stopping or evading)
  double time_to_collision_s = std::numeric_limits<double>::infinity();  // first hit at scale 1 (s after now_s)
  Action action = Action::kPass;
  // Smallest gap between the footprint and a point or a mover's disc (no margins) along the sent
  // command's prediction; +inf beyond CollisionMonitor::kClearanceRange_m.
  double min_clearance_m = std::numeric_limits<double>::infinity();
  std::string reason;  // what limited the command, and ignored input; empty for a plain kPass
};

class CollisionMonitor {
 public:
  // Clearances beyond this gap (m) are reported as +inf.
  static constexpr double kClearanceRange_m = 1.0;

  // Throws ParamError for invalid params or limits, a footprint radius <= 0 or a negative time
  // constant.
  CollisionMonitor(const CollisionMonitorParams& params, double footprint_radius_m, const VelocityLimits& limits,
                   double time_constant_s);
  // The robot's footprint radius, forward/yaw limits and tracking_time_constant_s.
  CollisionMonitor(const CollisionMonitorParams& params, const RobotProfile& robot);

  // One control cycle. Non-finite points are skipped, malformed mover predictions (non-finite
  // values, no states) ignored; a non-finite pose, velocity, command, time or period gives a stop
  // with the reason.
  MonitorDecision check(const MonitorInput& in) const;

  const CollisionMonitorParams& params() const { return params_; }

 private:
  CollisionMonitorParams params_;
  double radius_m_;
  VelocityLimits limits_;
  double tau_s_;
};

}  // namespace bipednav::control
