#pragma once

#include <optional>
#include <string_view>

#include "bipednav/common/outcome.hpp"
#include "bipednav/common/path.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/planning/local/moving_obstacle_yield.hpp"
#include "bipednav/planning/local/moving_obstacles.hpp"
#include "bipednav/planning/local/teb_params.hpp"
#include "bipednav/planning/local/tracker_params.hpp"

namespace bipednav::planning::local {

// One control cycle's answer. `result.outcome` is SUCCESS, NO_VALID_CMD, BLOCKED_PATH (the best
// trajectory enters lethal or inscribed cells: zero command; nothing was touched), OSCILLATION, or for bad input
// INVALID_PATH (empty or non-finite global plan), CTRL_TF_ERROR (non-finite robot pose or velocity), CTRL_MAP_ERROR
// (empty costmap), CTRL_OUT_OF_MAP (robot outside the local costmap). `cmd` is always finite and
// within the velocity/acceleration limits (zero on every outcome but SUCCESS).
struct LocalPlanResult {
  Result result;
  Twist cmd;
  Path trajectory;            // timed local trajectory in the map frame (for display)
  bool goal_reached = false;  // within the xy and yaw tolerance of the global plan's last pose
};

// A local planner / controller: one call per control cycle.
class LocalPlanner {
 public:
  virtual ~LocalPlanner() = default;
  // T_map_base: robot pose in the map frame; current_velocity in the base frame; global_plan and
  // local_costmap in the map frame; now_s: (simulated) time of the cycle.
  virtual LocalPlanResult compute(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                                  const mapping::Costmap2D& local_costmap, double now_s) = 0;
  // Forgets the warm start, the selected homotopy class and the oscillation history.
  virtual void reset() = 0;
  virtual std::string_view name() const = 0;
  // The position tolerance its parameters bring the robot inside at the goal.
  virtual double aimed_xy_goal_tolerance_m() const = 0;

  // The tracked obstacles to yield to (the navigator's tracker, fed from the sensors; not owned, it
  // must outlive the planner); none by default.
  void set_moving_obstacles(const MovingObstacleTracker* tracker) { moving_ = tracker; }
  void set_avoidance_params(const DynamicAvoidanceParams& params) { avoidance_ = (params.validate(), params); }
  const YieldDecision& last_yield() const { return last_yield_; }
  const MovingObstacleTracker* moving_obstacles() const { return moving_; }
  // The position tolerance the planner brings the robot inside at the goal: its parameters'
  // xy_goal_tolerance_m until set (> 0); the navigation server tightens it while the position
  // estimate is weak. <= 0: back to the parameters'.
  void set_xy_goal_tolerance(double m) { xy_goal_tolerance_m_ = m; }

 protected:
  double xy_goal_tolerance(double from_params_m) const {
    return xy_goal_tolerance_m_ > 0.0 ? xy_goal_tolerance_m_ : from_params_m;
  }
  // Replaces r.cmd by a command that yields to the predicted moving obstacles (see
  // yield_to_moving_obstacles); a failed cycle whose zero command would be run into becomes a
  // SUCCESS with the evasive command.
  void yield(LocalPlanResult& r, const Pose2& pose, const Twist& current, const mapping::Costmap2D& costmap,
             const VelocityLimits& lim, double period_s, double now_s);

  const MovingObstacleTracker* moving_ = nullptr;
  DynamicAvoidanceParams avoidance_;
  YieldDecision last_yield_;
  double xy_goal_tolerance_m_ = 0.0;
};

struct LocalPlannerParams {
  TebParams teb;
  TrackerParams tracker;
  DynamicAvoidanceParams avoidance;
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v.group("teb", teb);
    v.group("tracker", tracker);
    v.group("avoidance", avoidance);
  }
};

// The result for bad input (see plan_utils' check_inputs), or nullopt when the input is usable.
std::optional<LocalPlanResult> reject_bad_inputs(const Pose2& T_map_base, const Twist& current_velocity,
                                                 const Path& global_plan, const mapping::Costmap2D& local_costmap);

}  // namespace bipednav::planning::local
