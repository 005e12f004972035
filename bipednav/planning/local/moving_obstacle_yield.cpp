#include "bipednav/planning/local/moving_obstacle_yield.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"

namespace bipednav::planning::local {

namespace {

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

bool positive_time(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void DynamicAvoidanceParams::validate() const {
  require(positive_time(horizon_s), "dynamic_avoidance.horizon_s", "> 0");
  require(std::isfinite(robot_radius_m) && robot_radius_m >= 0.0, "dynamic_avoidance.robot_radius_m", ">= 0");
  require(std::isfinite(safety_margin_m) && safety_margin_m >= 0.0, "dynamic_avoidance.safety_margin_m", ">= 0");
  require(std::isfinite(prediction_growth_mps) && prediction_growth_mps >= 0.0,
          "dynamic_avoidance.prediction_growth_mps", ">= 0");
  require(positive_time(sim_step_s) && sim_step_s <= horizon_s, "dynamic_avoidance.sim_step_s", "in (0, horizon_s]");
  require(positive_time(static_check_s), "dynamic_avoidance.static_check_s", "> 0");
  // Holds between two rollout steps would repeat a candidate (the rollout brakes from a step on), and
  // a tiny step would make thousands of them on every control cycle.
  require(hold_step_s == 0.0 || (std::isfinite(hold_step_s) && hold_step_s >= sim_step_s),
          "dynamic_avoidance.hold_step_s", "0 (off) or >= sim_step_s");
}

namespace {

// Steps the velocity towards the target within the acceleration limits, then the pose.
struct Rollout {
  Pose2 pose;
  Twist vel;
};

void step(Rollout& r, const Twist& target, const VelocityLimits& lim, double dt) {
  const double dv = std::clamp(target.linear_x - r.vel.linear_x, -lim.acc_lim_x_mps2 * dt, lim.acc_lim_x_mps2 * dt);
  const double dw =
      std::clamp(target.angular_z - r.vel.angular_z, -lim.acc_lim_theta_radps2 * dt, lim.acc_lim_theta_radps2 * dt);
  r.vel.linear_x += dv;
  r.vel.angular_z += dw;
  r.pose = r.pose * Pose2{r.vel.linear_x * dt, 0.0, r.vel.angular_z * dt};
}

// The rolled-out robot against the predictions: the first time within the horizon at which it is
// within reach of a moving obstacle while the two still close in (infinity: never), and the
// smallest distance minus reach over the horizon.
struct RolloutCheck {
  double ttc_s = kUnbounded;
  double min_gap_m = kUnbounded;
};

RolloutCheck rollout_check(const Pose2& pose, const Twist& current, const Twist& target,
                           const std::vector<TrackedObstacle>& moving, const VelocityLimits& lim, double now_s,
                           const DynamicAvoidanceParams& p, std::vector<Pose2>* arc, double hold_s = kUnbounded) {
  // The prediction of obstacle i at now_s + dt: constant velocity.
  const auto at = [&](std::size_t i, double dt) -> Eigen::Vector2d { return moving[i].predict(now_s + dt); };
  Rollout r{pose, current};
  std::vector<double> prev(moving.size());
  for (std::size_t i = 0; i < moving.size(); ++i) prev[i] = (at(i, 0.0) - pose.position()).norm();
  if (arc) arc->assign(1, pose);
  RolloutCheck out;
  const int n = static_cast<int>(std::ceil(p.horizon_s / p.sim_step_s - 1e-9));
  for (int k = 1; k <= n; ++k) {
    const double t = k * p.sim_step_s;
    step(r, t - p.sim_step_s < hold_s - 1e-9 ? target : Twist{}, lim, p.sim_step_s);  // then braking
    if (arc && t <= p.static_check_s + 1e-9) arc->push_back(r.pose);
    for (std::size_t i = 0; i < moving.size(); ++i) {
      const double d = (at(i, t) - r.pose.position()).norm();
      const double reach = p.robot_radius_m + moving[i].radius_m + p.safety_margin_m + p.prediction_growth_mps * t;
      out.min_gap_m = std::min(out.min_gap_m, d - reach);
      if (!std::isfinite(out.ttc_s) && d < reach && d < prev[i] - 1e-6) out.ttc_s = t;
      prev[i] = d;
    }
  }
  return out;
}

}  // namespace

double time_to_collision(const Pose2& pose, const Twist& cmd, const std::vector<TrackedObstacle>& moving, double now_s,
                         const DynamicAvoidanceParams& params) {
  // Instant velocity changes: unlimited acceleration.
  const VelocityLimits lim{.max_vel_x_mps = 1e9,
                           .max_vel_x_backwards_mps = 1e9,
                           .max_vel_theta_radps = 1e9,
                           .acc_lim_x_mps2 = 1e9,
                           .acc_lim_theta_radps2 = 1e9};
  return rollout_check(pose, cmd, cmd, moving, lim, now_s, params, nullptr).ttc_s;
}

namespace {

// Candidates: the command slowed along its arc, then a coarse grid of forward, turning and
// backing commands, each held over the horizon; with hold_step_s, when none of those is free, the
// grid again, held for multiples of it and then braked to a stop (longest hold first, so of
// equally good ones the longest wins).
struct Candidate {
  Twist cmd;
  double hold_s = kUnbounded;
};

std::vector<Candidate> yield_candidates(const Twist& cmd, const VelocityLimits& lim, const DynamicAvoidanceParams& p) {
  std::vector<Candidate> cand;
  for (const double f : {0.75, 0.5, 0.25, 0.0}) cand.push_back({{f * cmd.linear_x, 0.0, f * cmd.angular_z}});
  cand.push_back({});
  const double vb = lim.max_vel_x_backwards_mps, vf = lim.max_vel_x_mps, wm = lim.max_vel_theta_radps;
  std::vector<double> holds{kUnbounded};
  if (p.hold_step_s > 0.0)
    for (int k = static_cast<int>(std::ceil(p.static_check_s / p.hold_step_s - 1e-9)) - 1; k >= 1; --k)
      holds.push_back(k * p.hold_step_s);
  for (const double hold : holds) {
    for (const double v : {-vb, -0.5 * vb, 0.0, 0.5 * vf, vf}) {
      if (v == 0.0 && std::isfinite(hold)) continue;  // turning in place then stopping: the held turn decides
      for (const double w : {-0.6 * wm, -0.3 * wm, 0.0, 0.3 * wm, 0.6 * wm}) cand.push_back({{v, 0.0, w}, hold});
    }
  }
  return cand;
}

// The chosen candidate (nullptr: none is collision-free against the costmap) and its time to
// collision.
struct Choice {
  const Candidate* best = nullptr;
  double ttc_s = kUnbounded;
};

Choice choose_candidate(const std::vector<Candidate>& cand, const Twist& cmd, const Pose2& pose, const Twist& cur,
                        const std::vector<TrackedObstacle>& moving, const mapping::Costmap2D& costmap,
                        const VelocityLimits& lim, double now_s, const DynamicAvoidanceParams& p) {
  const double vf = lim.max_vel_x_mps, wm = lim.max_vel_theta_radps;
  const auto deviation = [&](const Twist& c) {
    return std::abs(c.linear_x - cmd.linear_x) / std::max(vf, 1e-3) +
           0.5 * std::abs(c.angular_z - cmd.angular_z) / std::max(wm, 1e-3) + (c.linear_x < 0.0 ? 0.5 : 0.0);
  };
  // A collision-free candidate (against the predictions and the costmap) closest to the command;
  // when there is none, the one that keeps the largest gap to the moving obstacles.
  const Candidate* best = nullptr;
  bool best_free = false;
  double best_dev = kUnbounded, best_gap = -kUnbounded, best_ttc = kUnbounded;
  std::vector<Pose2> arc;
  for (const auto& c : cand) {
    if (std::isfinite(c.hold_s) && best_free) break;  // the held commands come first and one is free
    const RolloutCheck rc = rollout_check(pose, cur, c.cmd, moving, lim, now_s, p, &arc, c.hold_s);
    if (!poses_feasible(arc, costmap)) continue;
    const bool free = !std::isfinite(rc.ttc_s);
    const double dev = deviation(c.cmd);
    const bool better = best == nullptr || (free && !best_free) || (free && best_free && dev < best_dev) ||
                        (!free && !best_free && rc.min_gap_m > best_gap);
    if (!better) continue;
    best = &c, best_free = free, best_dev = dev, best_gap = rc.min_gap_m, best_ttc = rc.ttc_s;
  }
  return {best, best_ttc};
}

}  // namespace

YieldDecision yield_to_moving_obstacles(const Twist& cmd, const Pose2& pose, const Twist& current,
                                        const std::vector<TrackedObstacle>& moving, const mapping::Costmap2D& costmap,
                                        const VelocityLimits& lim, double period_s, double now_s,
                                        const DynamicAvoidanceParams& p) {
  YieldDecision out;
  out.cmd = out.target = cmd;
  out.ttc_s = kUnbounded;
  if (moving.empty() || !pose.is_finite() || !cmd.is_finite()) return out;
  const Twist cur = current.is_finite() ? current : Twist{};
  out.ttc_s = rollout_check(pose, cur, cmd, moving, lim, now_s, p, nullptr).ttc_s;
  if (!std::isfinite(out.ttc_s)) return out;

  const std::vector<Candidate> cand = yield_candidates(cmd, lim, p);
  const Choice choice = choose_candidate(cand, cmd, pose, cur, moving, costmap, lim, now_s, p);
  out.modified = true;
  if (choice.best == nullptr) {
    out.target = {};
    out.cmd = limit_velocity({}, cur, period_s, lim);
    out.ttc_s = rollout_check(pose, cur, Twist{}, moving, lim, now_s, p, nullptr).ttc_s;
    return out;
  }
  out.target = choice.best->cmd;
  out.cmd = limit_velocity(choice.best->cmd, cur, period_s, lim);
  out.ttc_s = choice.ttc_s;  // the arc the loop also asked for does not change it
  return out;
}

}  // namespace bipednav::planning::local
