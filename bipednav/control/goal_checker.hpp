#pragma once

#include "bipednav/common/pose2.hpp"

namespace bipednav::control {

// Goal tolerance of the thesis (0.2 m, 0.2 rad; section 6.2).
struct GoalCheckerParams {
  double xy_tolerance_m = 0.2;
  double yaw_tolerance_rad = 0.2;
  bool check_yaw = true;
  // Once the position was within tolerance, keep it as reached and only check the yaw (the
  // robot may drift a little while turning on the spot), until reset().
  bool stateful = false;

  void validate() const;
};

// Planar distance and absolute wrapped heading difference between pose and goal.
double goal_xy_error_m(const Pose2& pose, const Pose2& goal);
double goal_yaw_error_rad(const Pose2& pose, const Pose2& goal);

class GoalChecker {
 public:
  explicit GoalChecker(const GoalCheckerParams& params = {});

  // True when pose is within the tolerances of goal. Throws Error for non-finite poses.
  bool reached(const Pose2& pose, const Pose2& goal);
  // Forgets the latched position (stateful mode); call on a new goal.
  void reset() { xy_latched_ = false; }
  const GoalCheckerParams& params() const { return params_; }

 private:
  GoalCheckerParams params_;
  bool xy_latched_ = false;
};

}  // namespace bipednav::control
