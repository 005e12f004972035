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
}

double goal_xy_error_m(const Pose2& pose, const Pose2& goal) { return distance(pose, goal); }

double goal_yaw_error_rad(const Pose2& pose, const Pose2& goal) { return std::abs(angle_diff(pose.theta, goal.theta)); }

GoalChecker::GoalChecker(const GoalCheckerParams& params) : params_(params) { params_.validate(); }

bool GoalChecker::reached(const Pose2& pose, const Pose2& goal) {
  if (!pose.is_finite() || !goal.is_finite()) throw Error("GoalChecker::reached: pose or goal is not finite");
  const bool xy_ok = goal_xy_error_m(pose, goal) <= params_.xy_tolerance_m || (params_.stateful && xy_latched_);
  if (!xy_ok) return false;
  if (params_.stateful) xy_latched_ = true;
  return !params_.check_yaw || goal_yaw_error_rad(pose, goal) <= params_.yaw_tolerance_rad;
}

}  // namespace bipednav::control
