#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bipednav/common/body_response.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/planning/local/body_lag.hpp"
#include "bipednav/planning/local/teb_planner.hpp"
#include "local_test_utils.hpp"

namespace bipednav::planning::local {
namespace {

// Digit's profile (config/digit.yaml): limits and the walking controller's 0.3 s velocity lag.
constexpr double kDigitLagS = 0.3;
constexpr double kBodyStepS = 0.01;  // the simulator's body step
constexpr double kPeriodS = 0.1;     // control period

TebParams digit_teb(bool lag_model) {
  TebParams p;
  p.limits.velocity.max_vel_x_mps = 0.5;
  p.limits.velocity.max_vel_x_backwards_mps = 0.25;
  p.limits.velocity.max_vel_theta_radps = 0.6;
  p.limits.velocity.acc_lim_x_mps2 = 0.5;
  p.limits.velocity.acc_lim_theta_radps2 = 1.0;
  p.limits.min_obstacle_dist_m = 0.5;  // Digit's inscribed radius 0.38 m + 0.12 m
  p.control_period_s = kPeriodS;
  if (lag_model) p.response.time_constant_s = kDigitLagS;
  return p;
}

// The band's pose at time t_s after its start (linear between poses; the last pose after its end).
Eigen::Vector2d band_position_at(const Path& band, double t_s) {
  for (std::size_t k = 1; k < band.poses.size(); ++k) {
    if (band.times_s[k] >= t_s) {
      const double span = band.times_s[k] - band.times_s[k - 1];
      const double f = span > 0.0 ? (t_s - band.times_s[k - 1]) / span : 1.0;
      return (1.0 - f) * band.poses[k - 1].position() + f * band.poses[k].position();
    }
  }
  return band.poses.back().position();
}

struct LagRun {
  bool reached = false;
  double min_clearance_m = 1e9;   // body centre to the nearest obstacle disc's edge
  double max_band_error_m = 0.0;  // body position against the band's, lookahead_s after each cycle
  std::vector<Pose2> poses;       // the body at every cycle
  std::vector<Twist> cmds;
  std::vector<Outcome> outcomes;
};

struct Disc {
  double x, y, r;
};

// Closed loop: a unicycle whose velocities follow TEB's commands through Digit's first-order lag and
// acceleration limits (the simulator's body model, common/body_response.hpp), 10 body steps per cycle.
LagRun run_lagging_unicycle(TebPlanner& planner, const Path& plan, const mapping::Costmap2D& map,
                            const std::vector<Disc>& discs, int max_cycles, double lookahead_s) {
  const TebLimits& lim = planner.params().limits;
  LagRun run;
  Pose2 pose = plan.poses.front();
  Twist body;
  std::vector<Path> bands;
  for (int i = 0; i < max_cycles; ++i) {
    run.poses.push_back(pose);
    const auto r = planner.compute(pose, body, plan, map, i * kPeriodS);
    if (r.goal_reached) {
      run.reached = true;
      break;
    }
    bands.push_back(r.trajectory);
    run.cmds.push_back(r.cmd);
    run.outcomes.push_back(r.result.outcome);
    for (int s = 0; s < static_cast<int>(std::lround(kPeriodS / kBodyStepS)); ++s) {
      body.linear_x = track_first_order(body.linear_x, r.cmd.linear_x, kBodyStepS, kDigitLagS,
                                        lim.velocity.acc_lim_x_mps2 * kBodyStepS);
      body.angular_z = track_first_order(body.angular_z, r.cmd.angular_z, kBodyStepS, kDigitLagS,
                                         lim.velocity.acc_lim_theta_radps2 * kBodyStepS);
      pose = integrate_arc(pose, body.linear_x, body.angular_z, kBodyStepS);
    }
    for (const auto& d : discs)
      run.min_clearance_m = std::min(run.min_clearance_m, std::hypot(pose.x - d.x, pose.y - d.y) - d.r);
  }
  run.poses.push_back(pose);
  const int ahead = static_cast<int>(std::lround(lookahead_s / kPeriodS));
  for (std::size_t k = 0; k + ahead < run.poses.size() && k < bands.size(); ++k) {
    if (bands[k].poses.size() < 2) continue;  // turning on the goal: no band
    const Eigen::Vector2d planned = band_position_at(bands[k], lookahead_s);
    run.max_band_error_m = std::max(run.max_band_error_m, (run.poses[k + ahead].position() - planned).norm());
  }
  return run;
}

// A slalom: discs alternately left and right of a straight global path along x.
struct Slalom {
  std::vector<Disc> discs;
  mapping::Costmap2D map = test::empty_costmap(4.0, 0.0, 10.0);
  Path plan = test::straight_plan(0.0, 0.0, 8.0, 0.0);
  Slalom() {
    for (int i = 0; i < 4; ++i) discs.push_back({1.6 + 1.6 * i, i % 2 == 0 ? 0.3 : -0.3, 0.15});
    for (const auto& d : discs) test::add_disc(map, d.x, d.y, d.r, 0.38);
  }
};

}  // namespace

TEST(TebBodyLag, InvertingTheLagReachesTheTargetWithinTheHorizon) {
  BodyLag lag{kDigitLagS, {}};
  lag.limits.max_vel_x_mps = 0.5;
  lag.limits.max_vel_theta_radps = 0.6;
  lag.limits.acc_lim_x_mps2 = lag.limits.acc_lim_theta_radps2 = 100.0;  // the pure lag
  const Twist body{0.2, 0.0, -0.1};
  const Twist target{0.25, 0.0, 0.0};
  const Twist u = invert_body_lag(body, target, kPeriodS, lag);
  // u = v0 + (v - v0) / (1 - exp(-0.1 / 0.3)).
  const double alpha = 1.0 - std::exp(-kPeriodS / kDigitLagS);
  EXPECT_NEAR(u.linear_x, 0.2 + 0.05 / alpha, 1e-12);
  EXPECT_NEAR(u.angular_z, -0.1 + 0.1 / alpha, 1e-12);
  const Twist reached = predict_body_velocity(body, u, kPeriodS, lag);
  EXPECT_NEAR(reached.linear_x, target.linear_x, 1e-12);
  EXPECT_NEAR(reached.angular_z, target.angular_z, 1e-12);
  // Beyond the velocity limits the command is clamped; without a lag it is the target.
  EXPECT_EQ(invert_body_lag(body, {0.45, 0.0, 0.0}, kPeriodS, lag).linear_x, 0.5);
  EXPECT_EQ(invert_body_lag(body, target, kPeriodS, BodyLag{0.0, lag.limits}).linear_x, 0.25);
}

TEST(TebBodyLag, ThePredictionKeepsTheAccelerationLimit) {
  BodyLag lag{kDigitLagS, {}};
  lag.limits.max_vel_x_mps = 0.5;
  lag.limits.acc_lim_x_mps2 = 0.5;
  // From rest toward 0.5 m/s the lag asks 1.67 m/s^2 at first: the limit holds it to 0.5 m/s^2.
  EXPECT_NEAR(predict_body_velocity({}, {0.5, 0.0, 0.0}, kPeriodS, lag).linear_x, 0.05, 1e-12);
}

TEST(TebBodyLag, TheResponseParametersAreValidated) {
  TebParams p;
  p.response.time_constant_s = -0.1;
  EXPECT_THROW(p.validate(), ParamError);
  p.response.time_constant_s = 0.3;
  p.response.horizon_s = NAN;
  EXPECT_THROW(p.validate(), ParamError);
}

// A lagging unicycle (Digit's 0.3 s lag and acceleration limits) driven by TEB's commands through a
// slalom of four posts: with the lag model it passes within 25 s, never backs up, stays 0.38 m (Digit's
// inscribed radius) off every post and is within 0.2 m of where the band put it 0.5 s earlier.
TEST(TebBodyLag, WithTheLagModelALaggingWalkerFollowsTheBandThroughASlalom) {
  const Slalom s;
  TebPlanner planner(digit_teb(true));
  const auto run = run_lagging_unicycle(planner, s.plan, s.map, s.discs, 250, 0.5);
  EXPECT_TRUE(run.reached) << "at " << run.poses.back().x << " " << run.poses.back().y;
  EXPECT_GT(run.min_clearance_m, 0.38);
  EXPECT_LT(run.max_band_error_m, 0.2);
  for (const auto& c : run.cmds) EXPECT_GE(c.linear_x, 0.0);
}

// The same walker and slalom without the lag model: the body trails each planned swerve, the band
// re-plans against it, and the walker backs up and wavers: after 40 s it has not passed the slalom.
TEST(TebBodyLag, WithoutTheLagModelTheSameWalkerDoesNotPassTheSlalom) {
  const Slalom s;
  TebPlanner planner(digit_teb(false));
  const auto run = run_lagging_unicycle(planner, s.plan, s.map, s.discs, 400, 0.5);
  EXPECT_FALSE(run.reached);
  EXPECT_LT(run.poses.back().x, 7.0);
  EXPECT_TRUE(std::any_of(run.cmds.begin(), run.cmds.end(), [](const Twist& c) { return c.linear_x < -0.05; }));
}

}  // namespace bipednav::planning::local
