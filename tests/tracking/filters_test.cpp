#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/rng.hpp"
#include "bipednav/tracking/imm_cv_ct.hpp"
#include "bipednav/tracking/kalman_cv.hpp"
#include "bipednav/tracking/track_filter.hpp"

namespace bipednav::tracking {

TEST(KalmanCv, PredictionAndUpdateHaveTheirTextbookValues) {
  // Q for dt 0.5 s, q 2: q dt^3/3 = 1/12, q dt^2/2 = 1/4, q dt = 1.
  const Eigen::Matrix4d Q = cv_process_noise(0.5, 2.0);
  EXPECT_DOUBLE_EQ(Q(0, 0), 1.0 / 12.0);
  EXPECT_DOUBLE_EQ(Q(0, 2), 0.25);
  EXPECT_DOUBLE_EQ(Q(3, 3), 1.0);
  EXPECT_DOUBLE_EQ(Q(0, 1), 0.0);
  Eigen::Vector4d x(1.0, 2.0, 0.5, -1.0);
  Eigen::Matrix4d P = Eigen::Matrix4d::Identity();
  cv_predict(x, P, 0.5, 2.0);
  EXPECT_TRUE(x.isApprox(Eigen::Vector4d(1.25, 1.5, 0.5, -1.0)));
  EXPECT_DOUBLE_EQ(P(0, 0), 1.0 + 0.25 + 1.0 / 12.0);  // 1 + dt^2 + Q
  EXPECT_DOUBLE_EQ(P(0, 2), 0.5 + 0.25);
  // A measurement as uncertain as the prediction's position halves the difference.
  Eigen::Vector4d y = Eigen::Vector4d::Zero();
  Eigen::Matrix4d Py = Eigen::Matrix4d::Identity();
  position_update<4>(y, Py, Eigen::Vector2d(2.0, -2.0), Eigen::Matrix2d::Identity());
  EXPECT_TRUE(y.isApprox(Eigen::Vector4d(1.0, -1.0, 0.0, 0.0)));
  EXPECT_DOUBLE_EQ(Py(0, 0), 0.5);
  const Innovation in = position_innovation<4>(y, Py, Eigen::Vector2d(2.0, -1.0), Eigen::Matrix2d::Identity());
  EXPECT_DOUBLE_EQ(in.mahalanobis2(), 1.0 / 1.5);
}

TEST(ImmCvCt, CoordinatedTurnTransitionIsExact) {
  // Speed 1 m/s along x turning at pi/2 rad/s: after 1 s a quarter circle of radius 2/pi.
  Vector5d x;
  x << 0.0, 0.0, 1.0, 0.0, 0.5 * M_PI;
  Matrix5d F;
  const Vector5d y = ct_transition(x, 1.0, &F);
  EXPECT_NEAR(y(0), 2.0 / M_PI, 1e-12);
  EXPECT_NEAR(y(1), 2.0 / M_PI, 1e-12);
  EXPECT_NEAR(y(2), 0.0, 1e-12);
  EXPECT_NEAR(y(3), 1.0, 1e-12);
  // The Jacobian against central differences, also at a turn rate of zero.
  for (const double w : {0.5 * M_PI, 0.0}) {
    x(4) = w;
    ct_transition(x, 0.7, &F);
    for (int k = 0; k < 5; ++k) {
      Vector5d h = Vector5d::Zero();
      h(k) = 1e-6;
      const Vector5d numeric = (ct_transition(x + h, 0.7, nullptr) - ct_transition(x - h, 0.7, nullptr)) / 2e-6;
      EXPECT_TRUE(numeric.isApprox(F.col(k), 1e-6) || (numeric - F.col(k)).norm() < 1e-8) << "w " << w << " col " << k;
    }
  }
}

TEST(ImmCvCt, TurnModelTakesOverOnACircleAndNotOnALine) {
  // A target at 0.6 m/s on a circle of 2 m radius (0.3 rad/s), then one on a line, 1 cm noise.
  TrackerParams p;
  p.motion_model = "imm";
  p.accel_psd_m2ps3 = p.imm_turn_accel_psd_m2ps3 = 0.01;  // small: a straight line and a turn tell apart
  const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * 1e-4;
  Rng rng(3);
  const auto noisy = [&](const Eigen::Vector2d& z) {
    return Eigen::Vector2d(z + Eigen::Vector2d(rng.normal(0, 0.01), rng.normal(0, 0.01)));
  };
  const auto circle = [](double t) { return Eigen::Vector2d(2.0 * std::cos(0.3 * t), 2.0 * std::sin(0.3 * t)); };
  TrackFilter turn(circle(0.0), R, p), line(Eigen::Vector2d::Zero(), R, p);
  double max_err = 0.0;
  for (int k = 1; k <= 200; ++k) {
    const double t = 0.1 * k;
    turn.predict(0.1), line.predict(0.1);
    turn.update(noisy(circle(t)), R);
    line.update(noisy(Eigen::Vector2d(0.6 * t, 0.0)), R);
    if (t > 5.0) max_err = std::max(max_err, (turn.state().head<2>() - circle(t)).norm());
  }
  EXPECT_GT(turn.turn_probability(), 0.5);  // the turn model is the more probable one
  EXPECT_LT(line.turn_probability(), 0.4);
  EXPECT_LT(max_err, 0.03);
  const Eigen::Vector2d v(-0.6 * std::sin(6.0), 0.6 * std::cos(6.0));
  EXPECT_LT((turn.state().tail<2>() - v).norm(), 0.1);
}

}  // namespace bipednav::tracking
