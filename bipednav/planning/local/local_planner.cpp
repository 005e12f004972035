#include "bipednav/planning/local/local_planner.hpp"

#include "bipednav/common/error.hpp"
#include "bipednav/planning/local/plan_utils.hpp"

namespace bipednav::planning::local {

void LocalPlannerParams::validate() const {
  teb.validate();
  tracker.validate();
  avoidance.validate();
}

void LocalPlanner::yield(LocalPlanResult& r, const Pose2& pose, const Twist& current, const mapping::Costmap2D& costmap,
                         const VelocityLimits& lim, double period_s, double now_s) {
  last_yield_ = {};
  last_yield_.cmd = r.cmd;
  if (!moving_ || !moving_->params().enabled) return;
  const auto moving = moving_->moving(now_s);
  if (moving.empty()) return;
  // Only commands the planner produced or a stop are checked; bad input stays rejected.
  const bool failed = !r.result.ok();
  if (failed && r.result.outcome != Outcome::BLOCKED_PATH && r.result.outcome != Outcome::NO_VALID_CMD &&
      r.result.outcome != Outcome::OSCILLATION)
    return;
  const Twist cmd = failed ? Twist{} : r.cmd;
  last_yield_ = yield_to_moving_obstacles(cmd, pose, current, moving, costmap, lim, period_s, now_s, avoidance_);
  if (!last_yield_.modified) return;
  if (failed) {
    // Standing still would be run into: move away instead of failing.
    if (last_yield_.target.is_zero()) return;
    r.result = {Outcome::SUCCESS, "evading a moving obstacle (" + r.result.message + ")"};
  } else {
    r.result.message = "yielding to a moving obstacle";
  }
  r.cmd = last_yield_.cmd;
  r.goal_reached = false;
}

std::optional<LocalPlanResult> reject_bad_inputs(const Pose2& T_map_base, const Twist& current_velocity,
                                                 const Path& global_plan, const mapping::Costmap2D& local_costmap) {
  auto bad = check_inputs(T_map_base, current_velocity, global_plan, local_costmap);
  if (!bad) return std::nullopt;
  LocalPlanResult r;
  r.result = *bad;
  r.trajectory.frame_id = global_plan.frame_id;
  return r;
}

}  // namespace bipednav::planning::local
