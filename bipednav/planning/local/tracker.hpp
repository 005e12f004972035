#pragma once

#include <string_view>

#include "bipednav/planning/local/local_planner.hpp"
#include "bipednav/planning/local/plan_utils.hpp"
#include "bipednav/planning/local/tracker_params.hpp"

namespace bipednav::planning::local {

// Pure-pursuit steering: curvature 2 y / L^2 towards a lookahead point given in the base frame.
// Returns the desired (v, w) before acceleration limits; turns on the spot when the point lies
// more than rotate_in_place_angle off the heading.
Twist pure_pursuit_command(const Eigen::Vector2d& target_in_base, double dist_to_goal_m, const TrackerParams& p);

// The simple alternative local planner: follows the global plan with pure pursuit and stops with
// BLOCKED_PATH when the forward-simulated arc hits lethal or inscribed cells. A robot already in
// inscribed space may only follow arcs that keep its distance to the nearest lethal cell
// (poses_keep_clearance); when the tracked arc does not, it takes the command of a small grid
// (backing, turning, forward) whose arc gains the most clearance (escape), and stops with
// BLOCKED_PATH only when none keeps it.
class PathTracker : public LocalPlanner {
 public:
  explicit PathTracker(TrackerParams params);

  LocalPlanResult compute(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                          const mapping::Costmap2D& local_costmap, double now_s) override;
  void reset() override { holding_goal_ = false; }
  std::string_view name() const override { return "tracker"; }
  double aimed_xy_goal_tolerance_m() const override { return params_.xy_goal_tolerance_m; }

 private:
  LocalPlanResult follow(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                         const mapping::Costmap2D& local_costmap);
  // In inscribed space: replaces r's command and arc by the best clearance-keeping candidate;
  // false when the robot is not in inscribed space or no candidate keeps its clearance.
  bool escape(LocalPlanResult& r, const Pose2& T_map_base, const Twist& current_velocity, const Twist& desired,
              const mapping::Costmap2D& local_costmap) const;

  TrackerParams params_;
  bool holding_goal_ = false;  // approach_goal's hysteresis
};

}  // namespace bipednav::planning::local
