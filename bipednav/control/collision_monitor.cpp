#include "bipednav/control/collision_monitor.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bipednav/common/body_response.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::control {
namespace {

constexpr double kInfS = std::numeric_limits<double>::infinity();
constexpr int kBodySubsteps = 5;     // body integration steps per check step (0.01 s at the default sim_step_s)
constexpr double kRestSpeed = 1e-3;  // m/s and rad/s: below this on every axis the body counts as standing
constexpr double kMaxBrakeS = 20.0;  // braking is predicted at most this long

bool finite_nonneg(double v) { return std::isfinite(v) && v >= 0.0; }

// The body's state in the prediction: pose in the map frame, velocities in the base frame.
struct BodyState {
  Pose2 pose;
  double vx = 0.0, vy = 0.0, w = 0.0;
  bool at_rest() const { return std::abs(vx) < kRestSpeed && std::abs(vy) < kRestSpeed && std::abs(w) < kRestSpeed; }
};

// Pose after constant body velocities (vx, vy, w) for h seconds; integrate_arc without lateral motion.
Pose2 advance_body(const Pose2& p, double vx, double vy, double w, double h) {
  if (vy == 0.0) return integrate_arc(p, vx, w, h);
  const double dth = w * h;
  double fx, fy;  // displacement in the start frame
  if (std::abs(dth) < 1e-9) {
    fx = vx * h - 0.5 * vy * h * dth;
    fy = vy * h + 0.5 * vx * h * dth;
  } else {
    const double s = std::sin(dth), c = 1.0 - std::cos(dth);
    fx = (vx * s - vy * c) / w;
    fy = (vx * c + vy * s) / w;
  }
  return p * Pose2{fx, fy, dth};
}

// Positions of the body's centre at k * sim_step_s, k = 0, 1, ...
using Trajectory = std::vector<Eigen::Vector2d>;

// The body model of the simulator (common/body_response.hpp): per axis first-order tracking of the
// target with the acceleration limit, then the arc.
class BodyModel {
 public:
  BodyModel(const VelocityLimits& lim, double tau_s, double dt_s) : lim_(lim), tau_s_(tau_s), dt_s_(dt_s) {}

  void step(BodyState& b, const Twist& target) const {
    const double h = dt_s_ / kBodySubsteps;
    for (int i = 0; i < kBodySubsteps; ++i) {
      const Twist v = track_command({b.vx, b.vy, b.w}, target, h, tau_s_, lim_);
      b.vx = v.linear_x;
      b.vy = v.linear_y;
      b.w = v.angular_z;
      b.pose = advance_body(b.pose, b.vx, b.vy, b.w, h);
    }
  }

  // Follows `cmd` for follow_steps, brakes to rest under a zero command, then stands for stand_steps.
  Trajectory follow_then_stop(BodyState b, const Twist& cmd, int follow_steps, int stand_steps) const {
    Trajectory tr{b.pose.position()};
    for (int k = 0; k < follow_steps; ++k) {
      step(b, cmd);
      tr.push_back(b.pose.position());
    }
    const int max_brake = static_cast<int>(std::ceil(kMaxBrakeS / dt_s_));
    for (int k = 0; k < max_brake && !b.at_rest(); ++k) {
      step(b, Twist{});
      tr.push_back(b.pose.position());
    }
    tr.insert(tr.end(), stand_steps, b.pose.position());
    return tr;
  }

  // Holds `cmd` for `steps`.
  Trajectory hold(BodyState b, const Twist& cmd, int steps) const {
    Trajectory tr{b.pose.position()};
    for (int k = 0; k < steps; ++k) {
      step(b, cmd);
      tr.push_back(b.pose.position());
    }
    return tr;
  }

 private:
  VelocityLimits lim_;
  double tau_s_, dt_s_;
};

// The finite points inside a box, bucketed in square cells (counting sort by cell).
class PointGrid {
 public:
  PointGrid(std::span<const Eigen::Vector2d> points, Eigen::Vector2d lo, Eigen::Vector2d hi, double cell_m)
      : lo_(lo), cell_(cell_m) {
    const Eigen::Vector2d size = (hi - lo).cwiseMax(0.0);
    while ((size.x() / cell_ + 1.0) * (size.y() / cell_ + 1.0) > 1e6) cell_ *= 2.0;
    nx_ = static_cast<int>(size.x() / cell_) + 1;
    ny_ = static_cast<int>(size.y() / cell_) + 1;
    std::vector<int> cell_of;
    std::vector<const Eigen::Vector2d*> kept;
    start_.assign(static_cast<size_t>(nx_) * ny_ + 1, 0);
    for (const Eigen::Vector2d& p : points) {
      if (!p.allFinite() || (p.array() < lo.array()).any() || (p.array() > hi.array()).any()) continue;
      const int c = index(cell_x(p.x()), cell_y(p.y()));
      cell_of.push_back(c);
      kept.push_back(&p);
      ++start_[c + 1];
    }
    for (size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
    points_.resize(kept.size());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (size_t i = 0; i < kept.size(); ++i) points_[fill[cell_of[i]]++] = *kept[i];
  }

  bool empty() const { return points_.empty(); }

  // Calls f(q) for every point q in the cells overlapping the disc of radius r around p.
  template <class F>
  void near(const Eigen::Vector2d& p, double r, F&& f) const {
    if (points_.empty()) return;
    const int x0 = std::max(0, cell_x(p.x() - r)), x1 = std::min(nx_ - 1, cell_x(p.x() + r));
    const int y0 = std::max(0, cell_y(p.y() - r)), y1 = std::min(ny_ - 1, cell_y(p.y() + r));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        for (int i = start_[index(x, y)]; i < start_[index(x, y) + 1]; ++i) f(points_[i]);
  }

 private:
  int cell_x(double x) const { return std::clamp(static_cast<int>(std::floor((x - lo_.x()) / cell_)), -1, nx_); }
  int cell_y(double y) const { return std::clamp(static_cast<int>(std::floor((y - lo_.y()) / cell_)), -1, ny_); }
  int index(int x, int y) const { return y * nx_ + x; }

  Eigen::Vector2d lo_;
  double cell_;
  int nx_ = 1, ny_ = 1;
  std::vector<int> start_;  // points of cell c: [start_[c], start_[c + 1])
  std::vector<Eigen::Vector2d> points_;
};

// Whether a prediction can be used: finite radius, velocity and states, times increasing.
bool usable(const tracking::TrackPrediction& m) {
  if (!finite_nonneg(m.radius_m) || !m.velocity.allFinite() || m.states.empty()) return false;
  for (size_t i = 0; i < m.states.size(); ++i) {
    const auto& s = m.states[i];
    if (!std::isfinite(s.t_s) || !s.position.allFinite() || !s.covariance.allFinite()) return false;
    if (i > 0 && !(s.t_s > m.states[i - 1].t_s)) return false;
  }
  return true;
}

// The movers' predicted positions and keep-out distances (from the robot's centre) at
// now_s + k * dt_s, filled as far as asked.
class MoverTable {
 public:
  MoverTable(std::span<const tracking::TrackPrediction> movers, double now_s, double dt_s, double keep_out_m,
             double sigma_scale)
      : now_s_(now_s), dt_s_(dt_s), keep_out_m_(keep_out_m), sigma_scale_(sigma_scale) {
    for (const auto& m : movers)
      if (usable(m)) movers_.push_back(&m);
    ignored_ = static_cast<int>(movers.size() - movers_.size());
  }

  size_t size() const { return movers_.size(); }
  int ignored() const { return ignored_; }  // malformed predictions
  int id(size_t m) const { return movers_[m]->id; }
  double radius(size_t m) const { return movers_[m]->radius_m; }

  void fill(size_t steps) {
    const size_t n = movers_.size();
    for (size_t k = pos_.size() / std::max<size_t>(n, 1); n > 0 && k < steps; ++k)
      for (size_t m = 0; m < n; ++m) {
        Eigen::Matrix2d cov;
        pos_.push_back(at(*movers_[m], now_s_ + static_cast<double>(k) * dt_s_, cov));
        const double sigma = tracking::major_sigma(cov);
        reach_.push_back(keep_out_m_ + movers_[m]->radius_m + sigma_scale_ * sigma);
      }
  }
  const Eigen::Vector2d& position(size_t k, size_t m) const { return pos_[k * movers_.size() + m]; }
  double reach(size_t k, size_t m) const { return reach_[k * movers_.size() + m]; }

 private:
  // Position and covariance of m at t_s (see the header for the extrapolation).
  static Eigen::Vector2d at(const tracking::TrackPrediction& m, double t_s, Eigen::Matrix2d& cov) {
    const auto& s = m.states;
    if (t_s <= s.front().t_s) {
      cov = s.front().covariance;
      return s.front().position + m.velocity * (t_s - s.front().t_s);
    }
    if (t_s >= s.back().t_s) {
      cov = s.back().covariance;
      if (s.size() >= 2) {
        const auto& a = s[s.size() - 2];
        cov += (s.back().covariance - a.covariance) * ((t_s - s.back().t_s) / (s.back().t_s - a.t_s));
      }
      return s.back().position + m.velocity * (t_s - s.back().t_s);
    }
    const auto hi = std::upper_bound(s.begin(), s.end(), t_s, [](double t, const auto& st) { return t < st.t_s; });
    const auto lo = hi - 1;
    const double f = (t_s - lo->t_s) / (hi->t_s - lo->t_s);
    cov = lo->covariance + f * (hi->covariance - lo->covariance);
    return lo->position + f * (hi->position - lo->position);
  }

  std::vector<const tracking::TrackPrediction*> movers_;
  int ignored_ = 0;
  double now_s_, dt_s_, keep_out_m_, sigma_scale_;
  std::vector<Eigen::Vector2d> pos_;  // [k * movers + m]
  std::vector<double> reach_;
};

// The outcome of checking one trajectory.
struct TrajectoryCheck {
  double first_hit_s = kInfS;      // time of the first inadmissible step
  double min_clearance_m = kInfS;  // smallest gap between footprint and points or movers' discs
  std::string hit;                 // what was hit first
  bool mover_hit = false;          // a mover's prediction is hit at the first hit
  int hit_steps = 0;               // steps with a hit (counted when not stopping at the first)
};

struct CheckContext {
  const PointGrid& points;
  MoverTable& movers;
  double radius_m, point_bound_m, dt_s;
};

TrajectoryCheck check_trajectory(const Trajectory& tr, CheckContext& ctx, bool clearance, bool stop_at_hit) {
  TrajectoryCheck out;
  ctx.movers.fill(tr.size());
  const double bound = ctx.point_bound_m, bound2 = bound * bound;
  const double clear_r = ctx.radius_m + CollisionMonitor::kClearanceRange_m;
  for (size_t k = 0; k < tr.size(); ++k) {
    const Eigen::Vector2d& p = tr[k];
    const bool moved = k > 0 && (p - tr[k - 1]).squaredNorm() > 1e-18;
    bool hit = false;
    if (moved) {
      const Eigen::Vector2d& prev = tr[k - 1];
      ctx.points.near(p, bound, [&](const Eigen::Vector2d& q) {
        const double d2 = (p - q).squaredNorm();
        if (d2 < bound2 && std::sqrt(d2) < (prev - q).norm() - 1e-12) hit = true;
      });
      if (hit && out.hit.empty()) out.hit = "an obstacle point";
    }
    if (clearance && (k == 0 || moved))
      ctx.points.near(p, clear_r, [&](const Eigen::Vector2d& q) {
        out.min_clearance_m = std::min(out.min_clearance_m, (p - q).norm() - ctx.radius_m);
      });
    for (size_t m = 0; m < ctx.movers.size(); ++m) {
      const double d = (p - ctx.movers.position(k, m)).norm();
      if (d < ctx.movers.reach(k, m)) {
        if (!hit && out.hit.empty()) out.hit = "the prediction of mover " + std::to_string(ctx.movers.id(m));
        if (out.first_hit_s == kInfS) out.mover_hit = true;
        hit = true;
      }
      if (clearance) out.min_clearance_m = std::min(out.min_clearance_m, d - ctx.radius_m - ctx.movers.radius(m));
    }
    out.hit_steps += hit;
    if (hit && out.first_hit_s == kInfS) {
      out.first_hit_s = static_cast<double>(k) * ctx.dt_s;
      if (stop_at_hit) break;
    }
  }
  if (out.min_clearance_m > CollisionMonitor::kClearanceRange_m) out.min_clearance_m = kInfS;
  return out;
}

// Grows the box [lo, hi] to hold the trajectory.
void grow_box(const Trajectory& tr, Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
  for (const Eigen::Vector2d& p : tr) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
}

Twist scaled(const Twist& t, double s) { return Twist{s * t.linear_x, s * t.linear_y, s * t.angular_z}; }

// One axis after limit_velocity: a desired value nearer zero than the limiter's keeps braking
// (to zero at most), as the body's acceleration limits brake it anyway.
double brake_through(double desired, double limited) {
  if (limited > 0.0 && desired < limited) return std::max(desired, 0.0);
  if (limited < 0.0 && desired > limited) return std::min(desired, 0.0);
  return limited;
}

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

}  // namespace

void CollisionMonitorParams::validate() const {
  require(finite_nonneg(point_margin_m), "point_margin_m", ">= 0 m");
  require(finite_nonneg(mover_margin_m), "mover_margin_m", ">= 0 m");
  require(finite_nonneg(sigma_scale), "sigma_scale", ">= 0");
  require(finite_nonneg(standstill_s), "standstill_s", ">= 0 s");
  require(std::isfinite(sim_step_s) && sim_step_s > 0.0, "sim_step_s", "> 0 s");
  require(scale_steps >= 1, "scale_steps", ">= 1");
}

CollisionMonitor::CollisionMonitor(const CollisionMonitorParams& params, double footprint_radius_m,
                                   const VelocityLimits& limits, double time_constant_s)
    : params_(params), radius_m_(footprint_radius_m), limits_(limits), tau_s_(time_constant_s) {
  params_.validate();
  limits_.validate();
  require(std::isfinite(radius_m_) && radius_m_ > 0.0, "footprint_radius_m", "> 0 m");
  require(finite_nonneg(tau_s_), "tracking_time_constant_s", ">= 0 s");
}

CollisionMonitor::CollisionMonitor(const CollisionMonitorParams& params, const RobotProfile& robot)
    : CollisionMonitor(params, robot.footprint_radius_m, (robot.limits.validate(), robot.limits),
                       robot.tracking_time_constant_s) {}

MonitorDecision CollisionMonitor::check(const MonitorInput& in) const {
  using Action = MonitorDecision::Action;
  MonitorDecision out;
  const auto stop = [&](const std::string& why) {
    out.cmd = Twist{};
    out.scale = 0.0;
    out.action = Action::kStop;
    out.reason = why;
    return out;
  };
  if (!in.pose.is_finite()) return stop("non-finite pose");
  if (!in.velocity.is_finite()) return stop("non-finite measured velocity");
  if (!in.cmd.is_finite()) return stop("non-finite command");
  if (!std::isfinite(in.now_s)) return stop("non-finite time");
  if (!std::isfinite(in.period_s) || in.period_s <= 0.0) return stop("control period not finite and > 0");
  if (!params_.enabled) {
    out.cmd = in.cmd;
    return out;
  }

  const double dt = params_.sim_step_s;
  const BodyModel body(limits_, tau_s_, dt);
  BodyState start;
  start.pose = in.pose;
  start.vx = in.velocity.linear_x;
  start.vy = limits_.max_vel_y_mps > 0.0 ? in.velocity.linear_y : 0.0;
  start.w = in.velocity.angular_z;
  const int follow_steps = std::max(1, static_cast<int>(std::ceil(in.period_s / dt - 1e-9)));
  const int stand_steps = static_cast<int>(std::ceil(params_.standstill_s / dt - 1e-9));
  // The command as sent: the acceleration limits bound speeding up only.
  const auto limited = [&](const Twist& desired) {
    const Twist l = limit_velocity(desired, in.velocity, in.period_s, limits_);
    return Twist{brake_through(desired.linear_x, l.linear_x), brake_through(desired.linear_y, l.linear_y),
                 brake_through(desired.angular_z, l.angular_z)};
  };

  const int n = params_.scale_steps;
  std::vector<Twist> cmds;
  std::vector<Trajectory> trajs;
  Eigen::Vector2d lo = in.pose.position(), hi = lo;
  for (int i = 0; i <= n; ++i) {
    cmds.push_back(limited(scaled(in.cmd, i == n ? 0.0 : 1.0 - static_cast<double>(i) / n)));
    trajs.push_back(body.follow_then_stop(start, cmds.back(), follow_steps, stand_steps));
    grow_box(trajs.back(), lo, hi);
  }
  const double point_bound = radius_m_ + params_.point_margin_m;
  const double pad = std::max(point_bound, radius_m_ + kClearanceRange_m) + 1e-6;
  MoverTable movers(in.movers, in.now_s, dt, radius_m_ + params_.mover_margin_m, params_.sigma_scale);
  const auto build_grid = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    return PointGrid(in.points, a - Eigen::Vector2d::Constant(pad), b + Eigen::Vector2d::Constant(pad), point_bound);
  };
  const PointGrid grid = build_grid(lo, hi);
  CheckContext ctx{grid, movers, radius_m_, point_bound, dt};
  const std::string ignored =
      movers.ignored() > 0 ? " (" + std::to_string(movers.ignored()) + " malformed movers ignored)" : "";

  const TrajectoryCheck unscaled = check_trajectory(trajs[0], ctx, false, true);
  out.time_to_collision_s = unscaled.first_hit_s;
  for (int i = 0; i <= n; ++i) {
    const TrajectoryCheck c = i == 0 ? unscaled : check_trajectory(trajs[i], ctx, false, true);
    if (c.first_hit_s < kInfS) continue;
    out.scale = i == n ? 0.0 : 1.0 - static_cast<double>(i) / n;
    out.cmd = cmds[i];
    out.min_clearance_m = check_trajectory(trajs[i], ctx, true, false).min_clearance_m;
    out.action = i == 0 ? Action::kPass : i == n ? Action::kStop : Action::kSlow;
    if (i > 0)
      out.reason = "scale " + fmt(out.scale) + ": the command reaches " + unscaled.hit + " in " +
                   fmt(unscaled.first_hit_s) + " s";
    out.reason += ignored;
    return out;
  }

  // Not even stopping now is admissible. Braking into a point: stopping is all there is to do.
  const TrajectoryCheck standing = check_trajectory(trajs[n], ctx, true, false);
  if (!standing.mover_hit) {
    out.scale = 0.0;
    out.cmd = cmds[n];
    out.action = Action::kStop;
    out.min_clearance_m = standing.min_clearance_m;
    out.reason = "braking cannot stop short of " + standing.hit + " (in " + fmt(standing.first_hit_s) + " s)" + ignored;
    return out;
  }
  // A mover reaches the robot where it stops: the evasive command hit latest (ties: fewer steps hit,
  // then the larger clearance) if it beats standing.
  const int steps = static_cast<int>(trajs[n].size()) - 1;
  const double vb = limits_.max_vel_x_backwards_mps, vf = limits_.max_vel_x_mps, wm = limits_.max_vel_theta_radps;
  std::vector<Twist> evasive;
  if (vb > 0.0) evasive.insert(evasive.end(), {{-vb, 0, 0}, {-vb, 0, 0.5 * wm}, {-vb, 0, -0.5 * wm}});
  evasive.insert(evasive.end(), {{0, 0, wm}, {0, 0, -wm}, {vf, 0, 0}, {vf, 0, 0.5 * wm}, {vf, 0, -0.5 * wm}});
  evasive.insert(evasive.end(), {{vf, 0, wm}, {vf, 0, -wm}});
  if (limits_.max_vel_y_mps > 0.0)
    evasive.insert(evasive.end(), {{0, limits_.max_vel_y_mps, 0}, {0, -limits_.max_vel_y_mps, 0}});
  std::vector<Trajectory> etrajs;
  for (const Twist& e : evasive) {
    etrajs.push_back(body.hold(start, e, steps));
    grow_box(etrajs.back(), lo, hi);
  }
  const PointGrid egrid = build_grid(lo, hi);
  CheckContext ectx{egrid, movers, radius_m_, point_bound, dt};
  TrajectoryCheck best = standing;
  Twist best_cmd;
  for (size_t i = 0; i < evasive.size(); ++i) {
    const TrajectoryCheck c = check_trajectory(etrajs[i], ectx, true, false);
    const bool same_time = std::abs(c.first_hit_s - best.first_hit_s) <= 1e-9 || c.first_hit_s == best.first_hit_s;
    if (c.first_hit_s > best.first_hit_s + 1e-9 ||
        (same_time && (c.hit_steps < best.hit_steps ||
                       (c.hit_steps == best.hit_steps && c.min_clearance_m > best.min_clearance_m)))) {
      best = c;
      best_cmd = evasive[i];
    }
  }
  out.cmd = limited(best_cmd);
  out.scale = 0.0;
  out.action = Action::kEvade;
  out.min_clearance_m = best.min_clearance_m;
  out.reason = "cannot avoid contact by standing: " + standing.hit + " in " + fmt(standing.first_hit_s) +
               " s; evading (" + fmt(best_cmd.linear_x) + " m/s, " + fmt(best_cmd.angular_z) + " rad/s) hits in " +
               (best.first_hit_s < kInfS ? fmt(best.first_hit_s) + " s" : "none") + ignored;
  return out;
}

}  // namespace bipednav::control
