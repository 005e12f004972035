#include "bipednav/control/collision_monitor.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "bipednav/common/body_response.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::control {
namespace {

using Action = MonitorDecision::Action;
constexpr double kPeriodS = 0.1;   // control period
constexpr double kBodyDtS = 0.01;  // the simulator's step

// A lagging unicycle stepped like sim::RobotModel (without sway).
struct Body {
  Pose2 pose;
  double v = 0.0, w = 0.0;

  void step(const Twist& cmd, double tau_s, const VelocityLimits& lim) {
    const double v_target = std::clamp(cmd.linear_x, -lim.max_vel_x_backwards_mps, lim.max_vel_x_mps);
    const double w_target = std::clamp(cmd.angular_z, -lim.max_vel_theta_radps, lim.max_vel_theta_radps);
    v = track_first_order(v, v_target, kBodyDtS, tau_s, lim.acc_lim_x_mps2 * kBodyDtS);
    w = track_first_order(w, w_target, kBodyDtS, tau_s, lim.acc_lim_theta_radps2 * kBodyDtS);
    pose = integrate_arc(pose, v, w, kBodyDtS);
  }
  Twist velocity() const { return Twist{v, 0.0, w}; }
};

VelocityLimits test_limits() {
  VelocityLimits lim;
  lim.max_vel_x_mps = 0.6;
  lim.max_vel_x_backwards_mps = 0.15;
  lim.max_vel_theta_radps = 1.0;
  lim.acc_lim_x_mps2 = 0.5;
  lim.acc_lim_theta_radps2 = 1.5;
  return lim;
}

MonitorInput input(const Twist& cmd, const Body& b, std::span<const Eigen::Vector2d> points, double now_s,
                   std::span<const tracking::TrackPrediction> movers = {}) {
  MonitorInput in;
  in.cmd = cmd;
  in.pose = b.pose;
  in.velocity = b.velocity();
  in.points = points;
  in.movers = movers;
  in.now_s = now_s;
  in.period_s = kPeriodS;
  return in;
}

double nearest(const Eigen::Vector2d& p, const std::vector<Eigen::Vector2d>& points) {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& q : points) d = std::min(d, (p - q).norm());
  return d;
}

// A mover at `start` + velocity * t (t absolute), predicted as the tracker does: states every 0.1 s
// over 4 s from its estimate at estimate_s, the position's standard deviation growing 0.05 + 0.1 m/s.
tracking::TrackPrediction cv_mover(const Eigen::Vector2d& start, const Eigen::Vector2d& velocity, double radius_m,
                                   double estimate_s) {
  tracking::TrackPrediction m;
  m.id = 7;
  m.radius_m = radius_m;
  m.velocity = velocity;
  for (int j = 0; j <= 40; ++j) {
    const double h = 0.1 * j, sigma = 0.05 + 0.1 * h;
    m.states.push_back(
        {estimate_s + h, start + velocity * (estimate_s + h), sigma * sigma * Eigen::Matrix2d::Identity()});
  }
  return m;
}

void drive_at_wall(double tau_s) {
  SCOPED_TRACE("tau " + std::to_string(tau_s));
  const VelocityLimits lim = test_limits();
  const double radius = 0.2;
  const CollisionMonitorParams params;
  const CollisionMonitor monitor(params, radius, lim, tau_s);
  std::vector<Eigen::Vector2d> wall;
  for (int i = -75; i <= 75; ++i) {
    wall.emplace_back(3.0, 0.02 * i);
    wall.emplace_back(3.1, 0.02 * i);
  }
  Body body;
  double min_distance = std::numeric_limits<double>::infinity();
  int slowed = 0;
  for (int cycle = 0; cycle < 150; ++cycle) {
    const MonitorDecision d = monitor.check(input(Twist{0.5, 0.0, 0.0}, body, wall, cycle * kPeriodS));
    slowed += d.action == Action::kSlow || d.action == Action::kStop;
    for (int i = 0; i < 10; ++i) {
      body.step(d.cmd, tau_s, lim);
      min_distance = std::min(min_distance, nearest(body.pose.position(), wall));
    }
  }
  EXPECT_GT(slowed, 0);
  EXPECT_GT(min_distance, radius);  // never within the footprint of a wall point
  EXPECT_LT(std::abs(body.v), 0.01);
  const double gap = nearest(body.pose.position(), wall) - (radius + params.point_margin_m);
  EXPECT_GT(gap, -0.02);  // the margin is kept up to the prediction's discretisation
  EXPECT_LT(gap, 0.5);    // and the robot stops near it
}

TEST(CollisionMonitor, StopsShortOfAWallWithTheWalkersLag) { drive_at_wall(0.3); }

TEST(CollisionMonitor, StopsShortOfAWallWithTheDiffDrivesLag) { drive_at_wall(0.05); }

TEST(CollisionMonitor, WaitsOutsideACrossingMoversLaneThenGoesOn) {
  const VelocityLimits lim = test_limits();
  const double radius = 0.2, mover_radius = 0.25, tau = 0.3;
  const CollisionMonitor monitor({}, radius, lim, tau);
  // The mover crosses x = 0 along +y at 1 m/s, at y = 0 at t = 7.8 s, when the robot, without the
  // monitor, would be there too.
  const Eigen::Vector2d m0{0.0, -7.8}, mv{0.0, 1.0};
  Body body;
  body.pose = Pose2{-3.0, 0.0, 0.0};
  const std::vector<Eigen::Vector2d> no_points;
  double min_lane_distance_near = std::numeric_limits<double>::infinity();
  double min_mover_distance = std::numeric_limits<double>::infinity();
  double x_at_crossing = 0.0;
  double min_speed_before = std::numeric_limits<double>::infinity();
  for (int cycle = 0; cycle < 250; ++cycle) {
    const double now = cycle * kPeriodS;
    const std::vector<tracking::TrackPrediction> movers{cv_mover(m0, mv, mover_radius, now - 0.05)};
    const MonitorDecision d = monitor.check(input(Twist{0.5, 0.0, 0.0}, body, no_points, now, movers));
    ASSERT_NE(d.action, Action::kEvade) << d.reason;
    for (int i = 0; i < 10; ++i) {
      body.step(d.cmd, tau, lim);
      const double t = now + (i + 1) * kBodyDtS;
      const Eigen::Vector2d mover = m0 + mv * t;
      const Eigen::Vector2d p = body.pose.position();
      min_mover_distance = std::min(min_mover_distance, (p - mover).norm());
      if (std::abs(mover.y() - p.y()) < radius + mover_radius + 0.3)
        min_lane_distance_near = std::min(min_lane_distance_near, std::abs(p.x()));
      if (std::abs(t - 7.8) < 1e-9) x_at_crossing = p.x();
      if (t > 5.0 && t < 7.8) min_speed_before = std::min(min_speed_before, body.v);
    }
  }
  EXPECT_LT(min_speed_before, 0.25);  // it yielded (the approach model slows it to arrive after the mover)
  EXPECT_LT(x_at_crossing, -(radius + mover_radius));
  EXPECT_GT(min_lane_distance_near, radius + mover_radius);
  EXPECT_GT(min_mover_distance, radius + mover_radius + CollisionMonitorParams{}.mover_margin_m);
  EXPECT_GT(body.pose.x, 1.0);  // went on across the lane
}

TEST(CollisionMonitor, MovingAwayFromAPointInsideTheFootprintIsAllowed) {
  const CollisionMonitor monitor({}, 0.2, test_limits(), 0.3);
  const std::vector<Eigen::Vector2d> inside{{0.1, 0.0}};
  const Body body;
  const MonitorDecision back = monitor.check(input(Twist{-0.1, 0.0, 0.0}, body, inside, 0.0));
  EXPECT_EQ(back.action, Action::kPass) << back.reason;
  EXPECT_LT(back.cmd.linear_x, 0.0);
  const MonitorDecision turn = monitor.check(input(Twist{0.0, 0.0, 0.5}, body, inside, 0.0));
  EXPECT_EQ(turn.action, Action::kPass) << turn.reason;
  EXPECT_GT(turn.cmd.angular_z, 0.0);
  const MonitorDecision ahead = monitor.check(input(Twist{0.3, 0.0, 0.0}, body, inside, 0.0));
  EXPECT_EQ(ahead.action, Action::kStop);
  EXPECT_EQ(ahead.cmd.linear_x, 0.0);
  EXPECT_EQ(ahead.time_to_collision_s, 0.05);  // the first predicted step
  EXPECT_FALSE(ahead.reason.empty());
}

TEST(CollisionMonitor, BrakesWhenItCannotStopShortOfAPoint) {
  const CollisionMonitor monitor({}, 0.2, test_limits(), 0.3);
  Body body;
  body.v = 0.5;
  const std::vector<Eigen::Vector2d> close{{0.35, 0.0}};
  const MonitorDecision d = monitor.check(input(Twist{0.5, 0.0, 0.0}, body, close, 0.0));
  EXPECT_EQ(d.action, Action::kStop);
  EXPECT_TRUE(d.cmd.is_zero());
  EXPECT_NE(d.reason.find("braking cannot stop short"), std::string::npos) << d.reason;
  EXPECT_LT(d.time_to_collision_s, 0.5);
}

TEST(CollisionMonitor, SkipsNanPointsAndPassesWithoutObstacles) {
  const CollisionMonitor monitor({}, 0.2, test_limits(), 0.05);
  Body body;
  body.v = 0.3;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const MonitorDecision empty = monitor.check(input(Twist{0.3, 0.0, 0.1}, body, {}, 0.0));
  EXPECT_EQ(empty.action, Action::kPass);
  EXPECT_EQ(empty.scale, 1.0);
  EXPECT_DOUBLE_EQ(empty.cmd.linear_x, 0.3);
  EXPECT_TRUE(std::isinf(empty.time_to_collision_s));
  EXPECT_TRUE(std::isinf(empty.min_clearance_m));

  std::vector<Eigen::Vector2d> points{{0.35, 0.0}, {0.35, 0.1}};
  const MonitorDecision clean = monitor.check(input(Twist{0.3, 0.0, 0.0}, body, points, 0.0));
  points.insert(points.begin(), {Eigen::Vector2d{nan, 0.0}, Eigen::Vector2d{0.5, nan}});
  points.emplace_back(std::numeric_limits<double>::infinity(), 1.0);
  const MonitorDecision with_nan = monitor.check(input(Twist{0.3, 0.0, 0.0}, body, points, 0.0));
  EXPECT_NE(clean.action, Action::kPass);  // 0.1 m beyond the bound at 0.3 m/s: slowed
  EXPECT_EQ(with_nan.action, clean.action);
  EXPECT_EQ(with_nan.scale, clean.scale);
  EXPECT_EQ(with_nan.time_to_collision_s, clean.time_to_collision_s);
  EXPECT_NEAR(clean.min_clearance_m, with_nan.min_clearance_m, 1e-12);
}

TEST(CollisionMonitor, NonFiniteInputStops) {
  const CollisionMonitor monitor({}, 0.2, test_limits(), 0.05);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Body body;
  body.pose.x = nan;
  const MonitorDecision pose = monitor.check(input(Twist{0.3, 0.0, 0.0}, body, {}, 0.0));
  EXPECT_EQ(pose.action, Action::kStop);
  EXPECT_TRUE(pose.cmd.is_zero());
  EXPECT_NE(pose.reason.find("pose"), std::string::npos);
  const MonitorDecision cmd = monitor.check(input(Twist{nan, 0.0, 0.0}, Body{}, {}, 0.0));
  EXPECT_EQ(cmd.action, Action::kStop);
  EXPECT_TRUE(cmd.cmd.is_zero());
  Body fast;
  fast.w = std::numeric_limits<double>::infinity();
  EXPECT_EQ(monitor.check(input(Twist{0.3, 0.0, 0.0}, fast, {}, 0.0)).action, Action::kStop);
  // A malformed prediction is ignored, not trusted.
  tracking::TrackPrediction broken = cv_mover({1.0, 0.0}, {0.0, 0.0}, 0.25, 0.0);
  broken.states[3].position.x() = nan;
  const std::vector<tracking::TrackPrediction> movers{broken};
  const MonitorDecision d = monitor.check(input(Twist{0.1, 0.0, 0.0}, Body{}, {}, 0.0, movers));
  EXPECT_EQ(d.action, Action::kPass);
  EXPECT_NE(d.reason.find("malformed"), std::string::npos);
}

TEST(CollisionMonitor, EvadesAMoverComingHeadOn) {
  const VelocityLimits lim = test_limits();
  const double radius = 0.2, tau = 0.3;
  const CollisionMonitor monitor({}, radius, lim, tau);
  // The robot stands at the origin facing +x; a mover comes at it along -x at 1 m/s from 3 m.
  const Eigen::Vector2d m0{3.0, 0.0}, mv{-1.0, 0.0};
  const std::vector<tracking::TrackPrediction> movers{cv_mover(m0, mv, 0.25, 0.0)};
  const MonitorDecision d = monitor.check(input(Twist{0.3, 0.0, 0.0}, Body{}, {}, 0.0, movers));
  ASSERT_EQ(d.action, Action::kEvade) << d.reason;
  EXPECT_FALSE(d.cmd.is_zero());
  EXPECT_LT(d.time_to_collision_s, 2.5);
  // Following the evasion gains distance from the mover over standing.
  Body evading;
  Twist cmd = d.cmd;
  const std::vector<Eigen::Vector2d> no_points;
  for (int cycle = 0; cycle < 15; ++cycle) {
    if (cycle > 0) cmd = monitor.check(input(Twist{0.3, 0.0, 0.0}, evading, no_points, cycle * kPeriodS, movers)).cmd;
    for (int i = 0; i < 10; ++i) evading.step(cmd, tau, lim);
  }
  const Eigen::Vector2d mover = m0 + mv * 1.5;
  EXPECT_GT((evading.pose.position() - mover).norm(), mover.norm() + 0.05);
}

TEST(CollisionMonitor, ValidatesParameters) {
  EXPECT_NO_THROW(CollisionMonitorParams{}.validate());
  const auto bad = [](auto set) {
    CollisionMonitorParams p;
    set(p);
    return p;
  };
  EXPECT_THROW(bad([](auto& p) { p.point_margin_m = -0.1; }).validate(), ParamError);
  EXPECT_THROW(bad([](auto& p) { p.mover_margin_m = std::nan(""); }).validate(), ParamError);
  EXPECT_THROW(bad([](auto& p) { p.sigma_scale = -1.0; }).validate(), ParamError);
  EXPECT_THROW(bad([](auto& p) { p.standstill_s = std::numeric_limits<double>::infinity(); }).validate(), ParamError);
  EXPECT_THROW(bad([](auto& p) { p.sim_step_s = 0.0; }).validate(), ParamError);
  EXPECT_THROW(bad([](auto& p) { p.scale_steps = 0; }).validate(), ParamError);
  EXPECT_THROW(CollisionMonitor({}, 0.0, test_limits(), 0.1), ParamError);
  EXPECT_THROW(CollisionMonitor({}, 0.2, test_limits(), -0.1), ParamError);
}

}  // namespace
}  // namespace bipednav::control
