#include "bipednav/control/goal_checker.hpp"

#include <cmath>
#include <numbers>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::control {

void GoalCheckerParams::validate() const {
  require(std::isfinite(xy_tolerance_m) && xy_tolerance_m > 0.0, "xy_tolerance_m", "> 0 m");
  require(std::isfinite(yaw_tolerance_rad) && yaw_tolerance_rad > 0.0 && yaw_tolerance_rad <= std::numbers::pi,
          "yaw_tolerance_rad", "in (0, pi] rad");
  const auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  require(pos(trans_stopped_velocity_mps), "trans_stopped_velocity_mps", "> 0 m/s");
  require(pos(rot_stopped_velocity_radps), "rot_stopped_velocity_radps", "> 0 rad/s");
  require(std::isfinite(stopped_timeout_s) && stopped_timeout_s >= 0.0, "stopped_timeout_s", ">= 0 s");
}

double goal_xy_error_m(const Pose2& pose, const Pose2& goal) { return distance(pose, goal); }

double goal_yaw_error_rad(const Pose2& pose, const Pose2& goal) { return std::abs(angle_diff(pose.theta, goal.theta)); }

GoalChecker::GoalChecker(const GoalCheckerParams& params) : params_(params) { params_.validate(); }

bool GoalChecker::reached(const Pose2& pose, const Pose2& goal, const Twist& velocity, double now_s) {
  if (!pose.is_finite() || !goal.is_finite()) throw Error("GoalChecker::reached: pose or goal is not finite");
  if (!velocity.is_finite() || !std::isfinite(now_s))
    throw Error("GoalChecker::reached: velocity or time is not finite");
  const bool xy_ok = goal_xy_error_m(pose, goal) <= params_.xy_tolerance_m || (params_.stateful && xy_latched_);
  if (xy_ok && params_.stateful) xy_latched_ = true;
  const bool inside = xy_ok && (!params_.check_yaw || goal_yaw_error_rad(pose, goal) <= params_.yaw_tolerance_rad);
  if (!inside) {
    inside_since_s_ = -1.0;
    return false;
  }
  if (inside_since_s_ < 0.0) inside_since_s_ = now_s;
  if (!params_.require_stopped) return true;
  const bool stopped = std::abs(velocity.linear_x) <= params_.trans_stopped_velocity_mps &&
                       std::abs(velocity.angular_z) <= params_.rot_stopped_velocity_radps;
  return stopped || now_s - inside_since_s_ >= params_.stopped_timeout_s;
}

}  // namespace bipednav::control
