#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/outcome.hpp"
#include "bipednav/common/path.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/common/velocity_limits.hpp"
#include "bipednav/control/goal_checker.hpp"
#include "bipednav/control/oscillation_checker.hpp"
#include "bipednav/control/progress_checker.hpp"
#include "bipednav/mapping/global_costmap.hpp"
#include "bipednav/mapping/local_costmap.hpp"
#include "bipednav/planning/global/global_planner.hpp"
#include "bipednav/planning/local/local_planner.hpp"

namespace bipednav::navigation {

struct ServerParams {
  std::string global_planner = "dstar_lite";  // dstar_lite | astar
  planning::global::GlobalPlannerParams global;
  std::string local_planner = "teb";  // teb | tracker
  planning::local::LocalPlannerParams local;
  control::GoalCheckerParams goal;
  // The local planners aim at this share of the goal checker's xy and yaw tolerances (and hold
  // the goal out to the checker's xy tolerance), so that with the checker waiting for the robot to
  // stop, it comes to rest inside the tolerances rather than on their edge, where localization error
  // puts the true pose outside half the time. 0: the planners keep their own goal tolerances.
  double controller_goal_tolerance_fraction = 0.5;
  // While the position estimate is weak (Localizer::weakest_position_sigma_m), the error budget of
  // the xy tolerance goes to the estimate first: the planners aim at xy tolerance - 2 sigma when
  // that is tighter, but not below this share of the xy tolerance.
  double min_controller_goal_tolerance_fraction = 0.25;
  control::ProgressCheckerParams progress;
  control::OscillationCheckerParams oscillation;
  int controller_failures_allowed = 10;  // consecutive failed control cycles before exe_path fails
  double path_check_distance_m = 4.0;    // IsPathValid looks this far along the path
  double blocked_goal_timeout_s = 6.0;   // exe_path gives up on a goal blocked this long
  double relaxed_cost_weight_factor = 0.3;
  // The global planner keeps the robot's centre farther from obstacles than the global map's
  // inscribed radius (footprint + sway) by what the estimate leaves uncertain: this many position
  // standard deviations (RobotView::position_sigma_m, rounded up to whole cm). A gap open only to
  // a perfect estimate is then closed to the planner, which reports NO_PATH_FOUND instead of
  // sending the robot to squeeze through. No term for the map's quantisation: half a cell more
  // closed routes of generated clutter worlds that the robots pass (clutter_2, route margins
  // 0.14 / 0.32 m), as the maps' cells already sit outside the obstacles' surfaces. 0: the
  // inscribed radius alone.
  double plan_clearance_sigmas = 2.0;
  // Planner failures that may lead to a recovery for one goal (the planning sub-tree's recoveries,
  // and the 5 Hz replan failing once the old path is invalid), counted over the whole navigation as
  // Nav2 counts navigate_to_pose's retries (a path found in between does not restore them): a
  // planner that keeps failing, however often a recovery or a flickering map lets it find a path
  // for a while, ends the navigation with its outcome (NO_PATH_FOUND) instead of cycling until the
  // time limit.
  // 6, as Nav2's navigate_to_pose tree allows (4 ended a TurtleBot3 run in hexagon_dynamic whose
  // lanes the moving box blocks for a while).
  int planning_recoveries_allowed = 6;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("global_planner", global_planner);
    v.group("global", global);
    v("local_planner", local_planner);
    v.group("local", local);
    v.group("goal", goal);
    v("controller_goal_tolerance_fraction", controller_goal_tolerance_fraction);
    v("min_controller_goal_tolerance_fraction", min_controller_goal_tolerance_fraction);
    v.group("progress", progress);
    v.group("oscillation", oscillation);
    v("controller_failures_allowed", controller_failures_allowed);
    v("path_check_distance_m", path_check_distance_m);
    v("blocked_goal_timeout_s", blocked_goal_timeout_s);
    v("relaxed_cost_weight_factor", relaxed_cost_weight_factor);
    v("plan_clearance_sigmas", plan_clearance_sigmas);
    v("planning_recoveries_allowed", planning_recoveries_allowed);
  }
};

// How much farther than the inscribed radius the global planner keeps the robot's centre from
// obstacles with a position standard deviation of `position_sigma_m` (ServerParams::plan_clearance_sigmas).
double plan_clearance_allowance_m(const ServerParams& params, double position_sigma_m);

// Sets the local planners' goal tolerances from the goal checker's and
// controller_goal_tolerance_fraction (no change when it is 0).
void apply_controller_goal_tolerances(ServerParams& params);

// What the actions see of the robot this tick (filled in by the Navigator).
struct RobotView {
  double now_s = 0.0;
  Pose2 pose;      // T_map_base
  Twist velocity;  // base frame
  // The control period: the recoveries' commands change by at most the robot's acceleration
  // limits times this per cycle (limit_velocity from `velocity`).
  double period_s = 0.1;
  double position_sigma_m = 0.0;  // the pose estimate's largest position standard deviation
  // The body's measured velocity (odometry), when it differs from `velocity`, the velocity the
  // planners start from (a walker's reference braking from its last command): the goal checker's
  // "stopped" is the body's.
  std::optional<Twist> body_velocity = std::nullopt;
};

// One recovery as it ran, with what the recovery action reported (MBF outcomes 150-158).
struct RecoveryRecord {
  std::string name;  // the behavior tree leaf: BackUp, RotateInPlace, Wait, ClearCostmaps, RelaxConstraints
  double start_s = 0.0;
  double end_s = -1.0;  // -1 while it runs
  Result result;        // SUCCESS or a RECOVERY_* outcome (RECOVERY_CANCELED when halted)

  bool running() const { return end_s < 0.0; }
};

// One step of a long action: RUNNING with a command, or finished with an outcome.
struct ActionStep {
  enum class State { RUNNING, SUCCEEDED, FAILED } state = State::RUNNING;
  Result result;
};

// The Move Base Flex abstract navigation server (section 3.2.1): get_path, exe_path and the
// recovery behaviours on the navigator's costmaps, reporting MBF outcome codes. move_base is the
// behavior tree that sequences them (see Navigator). Holds references to the costmaps the
// Navigator owns (and its local planner a pointer to the Navigator's moving-obstacle tracker); the
// command it produces is read with command().
class NavigationServer {
 public:
  // `moving`: the tracked moving obstacles the local planner yields to; nullptr, said explicitly,
  // for a server whose planner yields to none.
  NavigationServer(ServerParams params, RobotProfile robot, mapping::GlobalCostmap& global,
                   mapping::LocalCostmap& local, const planning::local::MovingObstacleTracker* moving);
  NavigationServer(const NavigationServer&) = delete;
  NavigationServer& operator=(const NavigationServer&) = delete;

  void set_view(const RobotView& view) { view_ = view; }
  // Cells of the global map that changed since the last get_path (for D* Lite's repair).
  void add_global_changes(const mapping::ChangeSet& changes);

  // get_path: a global path from the robot to `goal` (outcomes 50-65).
  planning::global::PlanResult get_path(const Pose2& goal);
  // exe_path: one control cycle following `path` (outcomes 100-118); `first` on the first cycle.
  ActionStep exe_path(const Path& path, bool first);
  // The xy tolerance the local planner aims at this tick (see min_controller_goal_tolerance_fraction).
  double controller_xy_goal_tolerance() const;
  // Recoveries (outcomes 150-158); the long ones are stepped each tick.
  ActionStep back_up(double distance_m, double speed_mps, bool first);
  ActionStep rotate_in_place(double angle_rad, bool first);
  ActionStep wait(double duration_s, bool first);
  Result clear_costmaps();
  Result relax_constraints();
  void stop() { cmd_ = {}; }
  // Admits one more planning recovery while this goal's planning_recoveries_allowed last (the
  // PlanningRecoveryAllowed condition; each admission counts).
  bool admit_planning_recovery();
  // A running recovery was halted (preempted, or the safety gate took over): it ends
  // RECOVERY_CANCELED and the robot stops.
  void cancel_recovery();

  // Conditions.
  // Not const: the goal checker latches the position once it was within tolerance (stateful mode).
  bool goal_reached(const Pose2& goal);
  Result goal_valid(const Pose2& goal) const;  // SUCCESS, PLAN_OUT_OF_MAP, BLOCKED_GOAL
  Result start_valid() const;                  // SUCCESS, INVALID_START (not finite / off the map), BLOCKED_START
  bool path_valid(const Path& path) const;
  bool can_rotate_in_place() const { return robot_.can_rotate_in_place; }

  // A new goal: forget constraint relaxations and the controller's history.
  void on_new_goal();

  const Twist& command() const { return cmd_; }
  const Path& local_trajectory() const { return trajectory_; }
  const planning::local::LocalPlanner& local_planner() const { return *local_planner_; }
  // The robot's command limits (the recoveries ramp within them).
  const VelocityLimits& velocity_limits() const { return limits_; }
  const planning::global::PlanResult& last_plan() const { return last_plan_; }
  std::size_t plans() const { return plans_; }
  std::size_t recoveries() const { return recoveries_; }
  // The latest recoveries (at most kRecoveryLogSize, oldest first) with their outcomes.
  static constexpr std::size_t kRecoveryLogSize = 256;
  const std::vector<RecoveryRecord>& recovery_log() const { return recovery_log_; }
  // Process CPU time spent in the global planner (get_path) and the local planner (exe_path).
  double global_planner_cpu_ms() const { return global_planner_cpu_ms_; }
  double local_planner_cpu_ms() const { return local_planner_cpu_ms_; }

 private:
  void make_global_planner(bool relaxed);
  // The min_impassable_cost of the global planner's cost model for this tick's position sigma.
  int plan_impassable_cost() const;
  bool recovery_running() const { return !recovery_log_.empty() && recovery_log_.back().running(); }
  void begin_recovery(const char* name);
  Result end_recovery(Result result);  // closes the running record; returns `result`
  ActionStep end_recovery(ActionStep step);
  // A recovery's motion command: `target` reached from the current velocity within the robot's
  // velocity and acceleration limits over one control period.
  Twist ramp_to(const Twist& target) const;

  ServerParams params_;
  RobotProfile robot_;
  VelocityLimits limits_;
  mapping::GlobalCostmap& global_;
  mapping::LocalCostmap& local_;
  std::unique_ptr<planning::global::GlobalPlanner> global_planner_;
  std::unique_ptr<planning::local::LocalPlanner> local_planner_;
  control::GoalChecker goal_checker_;
  control::ProgressChecker progress_;
  control::OscillationChecker oscillation_;
  RobotView view_;
  mapping::ChangeSet pending_changes_;
  Twist cmd_;
  Path trajectory_;
  planning::global::PlanResult last_plan_;
  int ctrl_failures_ = 0;
  double blocked_since_s_ = -1.0;
  bool relaxed_ = false;
  int planning_recoveries_ = 0;                // admitted for this goal
  int impassable_cost_ = mapping::kInscribed;  // the global planner's, from plan_impassable_cost()
  std::size_t plans_ = 0;
  std::size_t recoveries_ = 0;
  double global_planner_cpu_ms_ = 0.0, local_planner_cpu_ms_ = 0.0;
  // Recovery state.
  Pose2 recovery_start_pose_;
  double recovery_start_s_ = 0.0;
  double rotated_rad_ = 0.0;
  double last_yaw_ = 0.0;
  std::vector<RecoveryRecord> recovery_log_;
};

}  // namespace bipednav::navigation
