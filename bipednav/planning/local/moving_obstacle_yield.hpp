#pragma once

#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/planning/local/moving_obstacles.hpp"
#include "bipednav/planning/local/plan_utils.hpp"

namespace bipednav::planning::local {

// Yielding to moving obstacles: the command is checked against the constant-velocity predictions
// of the moving tracks over horizon_s; when the robot would come closer than its radius plus the
// blob's plus the margin, a safer command is chosen among slower, turning and backing candidates
// (collision-free against the costmap): the one closest to the planner's command that no moving
// obstacle runs into, else the one that keeps the largest gap to them.
// Yielding runs whenever the planner is given a tracker whose MovingObstacleParams::enabled is set
// (the one switch for tracking and yielding).
struct DynamicAvoidanceParams {
  double horizon_s = 3.0;
  double robot_radius_m = 0.25;
  double safety_margin_m = 0.15;
  // The reach grows this much per second of prediction: a constant-velocity prediction misses the
  // obstacle's turns (hexagon_dynamic's box turns a corner 0.3 m from a robot waiting for it).
  double prediction_growth_mps = 0.05;
  double sim_step_s = 0.1;
  double static_check_s = 1.5;  // candidate arcs are checked against the costmap this far ahead
  // Candidates that move and then stop, when no held candidate is free: the grid of commands
  // again, each held for a multiple of hold_step_s shorter than static_check_s and then braked to
  // a stop within the acceleration limits (checked against the predictions and the costmap as
  // braked). A robot in a mover's lane between two obstacles can then step aside, where every
  // command held for static_check_s runs into one of them and standing still was the only
  // candidate left. Cause addressed: hexagon_dynamic/turtlebot3 seed 8, the robot in the box's
  // lane between the cylinders at (-1.1, 0) and (0, 0) (0.8 m between their surfaces) stopped at
  // 45.4 s with the box 0.3 m away and was run into. 0: off (only held commands); else at least
  // sim_step_s. On for the TurtleBot3 (config/turtlebot3.params.yaml, 0.25 s).
  double hold_step_s = 0.0;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("horizon_s", horizon_s);
    v("robot_radius_m", robot_radius_m);
    v("safety_margin_m", safety_margin_m);
    v("prediction_growth_mps", prediction_growth_mps);
    v("sim_step_s", sim_step_s);
    v("static_check_s", static_check_s);
    v("hold_step_s", hold_step_s);
  }
};

// Time until the robot driving (v, w) from `pose` at now_s first comes within reach of a moving
// obstacle's prediction; +infinity when not within horizon_s.
double time_to_collision(const Pose2& pose, const Twist& cmd, const std::vector<TrackedObstacle>& moving, double now_s,
                         const DynamicAvoidanceParams& params);

struct YieldDecision {
  Twist cmd;
  Twist target;           // the chosen candidate before the acceleration limits
  bool modified = false;  // the command was replaced
  double ttc_s = 0.0;     // time to collision of the returned command (inf: none predicted)
};

// Keeps `cmd` when no collision with a moving obstacle is predicted, else returns the safest
// candidate (see DynamicAvoidanceParams). The result is within the velocity and acceleration
// limits from `current`.
YieldDecision yield_to_moving_obstacles(const Twist& cmd, const Pose2& pose, const Twist& current,
                                        const std::vector<TrackedObstacle>& moving, const mapping::Costmap2D& costmap,
                                        const VelocityLimits& lim, double period_s, double now_s,
                                        const DynamicAvoidanceParams& params);

}  // namespace bipednav::planning::local
