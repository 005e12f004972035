#pragma once

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/twist.hpp"

namespace bipednav::control {

// Goal tolerance of the thesis (0.2 m, 0.2 rad; section 6.2).
struct GoalCheckerParams {
  double xy_tolerance_m = 0.2;
  double yaw_tolerance_rad = 0.2;
  bool check_yaw = true;
  // Once the position was within tolerance, keep it as reached and only check the yaw (the
  // robot may drift a little while turning on the spot), until reset().
  bool stateful = false;
  // Nav2's StoppedGoalChecker: the goal counts as reached only once the robot is inside the
  // tolerances *and* stopped (|linear_x| and |angular_z| of its velocity at most these), so a robot
  // passing through the tolerance's edge is not stopped there: the controllers, aiming at a share of
  // the tolerances (ServerParams::controller_goal_tolerance_fraction), bring it to rest inside. The
  // defaults sit twice the TurtleBot3 odometry's velocity noise (0.05 m/s) above zero. A walker's
  // lateral sway is not counted (it is not motion towards the goal).
  bool require_stopped = true;
  double trans_stopped_velocity_mps = 0.1;
  double rot_stopped_velocity_radps = 0.15;
  // Fallback: inside the tolerances this long without stopping still counts as reached, so a robot
  // whose velocity never settles cannot hang at the goal.
  double stopped_timeout_s = 3.0;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("xy_tolerance_m", xy_tolerance_m);
    v("yaw_tolerance_rad", yaw_tolerance_rad);
    v("check_yaw", check_yaw);
    v("stateful", stateful);
    v("require_stopped", require_stopped);
    v("trans_stopped_velocity_mps", trans_stopped_velocity_mps);
    v("rot_stopped_velocity_radps", rot_stopped_velocity_radps);
    v("stopped_timeout_s", stopped_timeout_s);
  }
};

// Planar distance and absolute wrapped heading difference between pose and goal.
double goal_xy_error_m(const Pose2& pose, const Pose2& goal);
double goal_yaw_error_rad(const Pose2& pose, const Pose2& goal);

class GoalChecker {
 public:
  explicit GoalChecker(const GoalCheckerParams& params = {});

  // True when pose is within the tolerances of goal and (require_stopped) the robot is stopped or has
  // been inside the tolerances for stopped_timeout_s (timed on now_s). Throws Error for non-finite
  // poses or velocities.
  bool reached(const Pose2& pose, const Pose2& goal, const Twist& velocity, double now_s);
  // The same for a robot at rest.
  bool reached(const Pose2& pose, const Pose2& goal) { return reached(pose, goal, Twist{}, 0.0); }
  // Forgets the latched position (stateful mode) and the time inside; call on a new goal.
  void reset() {
    xy_latched_ = false;
    inside_since_s_ = -1.0;
  }
  const GoalCheckerParams& params() const { return params_; }

 private:
  GoalCheckerParams params_;
  bool xy_latched_ = false;
  double inside_since_s_ = -1.0;  // when the pose last entered the tolerances (< 0: outside)
};

}  // namespace bipednav::control
