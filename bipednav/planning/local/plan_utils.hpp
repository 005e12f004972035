#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "bipednav/common/outcome.hpp"
#include "bipednav/common/path.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/common/velocity_limits.hpp"
#include "bipednav/mapping/costmap2d.hpp"

namespace bipednav::planning::local {

// Rejects bad input with a typed outcome: non-finite pose/velocity (CTRL_TF_ERROR), empty or
// non-finite plan (INVALID_PATH), empty costmap (CTRL_MAP_ERROR), robot off the map (CTRL_OUT_OF_MAP).
std::optional<Result> check_inputs(const Pose2& T_map_base, const Twist& velocity, const Path& plan,
                                   const mapping::Costmap2D& costmap);

// The local goal: the last pose of the global plan that is still inside the costmap window (with
// a margin) and within lookahead_m of arc length from the plan point nearest to the robot.
struct LocalGoal {
  Pose2 goal;
  std::vector<Eigen::Vector2d> via_points;  // plan points between robot and goal, every via_sep_m
  bool is_final = false;                    // the goal is the plan's last pose
};
LocalGoal select_local_goal(const Path& plan, const Pose2& T_map_base, const mapping::Costmap2D& costmap,
                            double lookahead_m, double margin_m, double via_sep_m);

// True when none of the poses (and the straight pieces between consecutive ones, sampled at the
// grid resolution) lies in a lethal cell, or in an inscribed one unless the robot is already in
// inscribed space. Off-map and unknown cells count as free.
bool poses_feasible(const std::vector<Pose2>& poses, const mapping::Costmap2D& costmap);

// Distance from (x, y) to the centre of the nearest lethal cell, searched out to max_m; +inf when
// no lethal cell lies that close. Off-map cells count as free. `nearest` (if given) gets that
// cell's centre when one was found.
double lethal_clearance(const mapping::Costmap2D& costmap, double x, double y, double max_m,
                        Eigen::Vector2d* nearest = nullptr);

// poses_feasible without its loophole: a robot already in inscribed space may follow the poses
// only if none of them (and of the points between, sampled as poses_feasible does) that lies in
// inscribed or lethal space is closer to a lethal cell than the first pose (lethal_clearance), and
// none is lethal unless the first one is. Every cell within the inscribed radius costs the same,
// so without this an arc could go on towards the obstacle. Outside inscribed space: poses_feasible.
bool poses_keep_clearance(const std::vector<Pose2>& poses, const mapping::Costmap2D& costmap);

// Near the final goal: zero once within both tolerances, else a turn on the spot to the goal yaw.
struct GoalApproach {
  bool near = false;     // within the xy tolerance
  bool reached = false;  // ... and the yaw tolerance
  Twist cmd;             // desired (unclamped) command
};
// Within xy_tol_m of the goal: turn on the spot to its yaw. With `holding` (the caller's state,
// cleared on a new goal) the approach stays near once it got within xy_tol_m until the robot is more
// than release_m away (hysteresis: localization noise and a walker's sway while turning do not send
// it back to path following for a few centimetres); release_m <= xy_tol_m or no `holding`: none.
GoalApproach approach_goal(const Pose2& T_map_base, const Pose2& goal, double xy_tol_m, double yaw_tol_rad,
                           double rotate_gain, double max_vel_theta_radps, double release_m = 0.0,
                           bool* holding = nullptr);

// The distance from p to the segment [a, b].
double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b);

// Detects oscillation in the command history: the mean velocities stay small while the yaw rate
// (or the forward speed) keeps changing sign.
class OscillationDetector {
 public:
  OscillationDetector(int window, double max_vel_x_mps, double max_vel_theta_radps);
  void update(const Twist& cmd);
  bool oscillating() const;
  void clear() { history_.clear(); }

 private:
  std::size_t window_;
  double max_v_, max_w_;
  std::vector<Twist> history_;
};

}  // namespace bipednav::planning::local
