#include "bipednav/localization/localizer.hpp"

#include <gtest/gtest.h>

#include "bipednav/common/error.hpp"

namespace bipednav::localization {
namespace {

Odometry odometry_at(double t_s, double x_m) {
  Odometry o;
  o.stamp_s = t_s;
  o.T_odom_base = Pose2{x_m, 0.0, 0.0};
  return o;
}

// Without LiDAR corrections the position is dead reckoning: its sigma grows by
// odometry_drift_ratio per metre from scan_position_sigma_m, equally along and across.
TEST(Localizer, PositionSigmaGrowsWithTheDistanceTheOdometryCarries) {
  LocalizerParams p;
  p.method = "odometry";
  p.odometry_drift_ratio = 0.03;
  p.scan_position_sigma_m = 0.02;
  RobotProfile robot;
  Localizer loc(p, robot, Pose2{});
  for (int k = 0; k <= 50; ++k) loc.add_odometry(odometry_at(0.1 * k, 0.1 * k));  // 5 m along x
  EXPECT_NEAR(loc.position_sigma_m({1.0, 0.0}), 0.02 + 0.03 * 5.0, 1e-9);
  EXPECT_NEAR(loc.position_sigma_m({0.0, 2.0}), 0.02 + 0.03 * 5.0, 1e-9);
  Eigen::Vector2d d;
  EXPECT_NEAR(loc.weakest_position_sigma_m(&d), 0.17, 1e-9);
  EXPECT_NEAR(d.norm(), 1.0, 1e-9);
  loc.reset(Pose2{1.0, 2.0, 0.0});  // a pose given from outside counts as known
  EXPECT_NEAR(loc.weakest_position_sigma_m(), 0.02, 1e-9);
}

TEST(Localizer, RejectsANegativeDriftRatio) {
  LocalizerParams p;
  p.odometry_drift_ratio = -0.1;
  EXPECT_THROW(p.validate(), ParamError);
  p = LocalizerParams{};
  p.scan_position_sigma_m = 0.0;
  EXPECT_THROW(p.validate(), ParamError);
}

}  // namespace
}  // namespace bipednav::localization
