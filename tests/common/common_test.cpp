#include <gtest/gtest.h>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/clock.hpp"
#include "bipednav/common/outcome.hpp"
#include "bipednav/common/path.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/se3.hpp"

using namespace bipednav;

TEST(Angles, NormalizeWrapsIntoHalfOpenInterval) {
  EXPECT_NEAR(normalize_angle(3 * std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(normalize_angle(-std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(normalize_angle(2 * std::numbers::pi + 0.1), 0.1, 1e-12);
  EXPECT_NEAR(angle_diff(0.1, -0.1), 0.2, 1e-12);
  EXPECT_NEAR(angle_diff(-3.1, 3.1), 2 * std::numbers::pi - 6.2, 1e-12);
}

TEST(Pose2, ComposeAndInverseAreConsistent) {
  const Pose2 a{1.0, 2.0, 0.5}, b{-0.3, 0.7, -1.2};
  const Pose2 c = a * b;
  const Pose2 back = a.inverse() * c;
  EXPECT_NEAR(back.x, b.x, 1e-12);
  EXPECT_NEAR(back.y, b.y, 1e-12);
  EXPECT_NEAR(back.theta, b.theta, 1e-12);
  const Pose2 id = a * a.inverse();
  EXPECT_NEAR(id.x, 0.0, 1e-12);
  EXPECT_NEAR(id.y, 0.0, 1e-12);
  EXPECT_NEAR(id.theta, 0.0, 1e-12);
  const Pose2 quarter{0, 0, std::numbers::pi / 2};
  const Eigen::Vector2d p = quarter.transform({1.0, 0.0});
  EXPECT_NEAR(p.x(), 0.0, 1e-12);
  EXPECT_NEAR(p.y(), 1.0, 1e-12);
}

TEST(SE3, RpyRoundTripAndPose2Projection) {
  const SE3 T = make_se3(1, 2, 3, 0.1, -0.2, 0.3);
  const Eigen::Vector3d rpy = matrix_to_rpy(T.linear());
  EXPECT_NEAR(rpy.x(), 0.1, 1e-12);
  EXPECT_NEAR(rpy.y(), -0.2, 1e-12);
  EXPECT_NEAR(rpy.z(), 0.3, 1e-12);
  const Pose2 p = pose2_from_se3(se3_from_pose2({1, -1, 2.0}));
  EXPECT_NEAR(p.x, 1, 1e-12);
  EXPECT_NEAR(p.y, -1, 1e-12);
  EXPECT_NEAR(p.theta, 2.0, 1e-12);
}

TEST(SE3, ExpOfPureRotationAndInterpolation) {
  Eigen::Matrix<double, 6, 1> xi;
  xi << 0, 0, 0, 0, 0, std::numbers::pi / 2;
  const SE3 T = se3_exp(xi);
  EXPECT_NEAR((T * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, 1e-12);
  const SE3 mid = se3_interpolate(SE3::Identity(), make_se3(2, 0, 0, 0, 0, 1.0), 0.5);
  EXPECT_NEAR(mid.translation().x(), 1.0, 1e-12);
  EXPECT_NEAR(matrix_to_rpy(mid.linear()).z(), 0.5, 1e-12);
}

TEST(Path, LengthSumsSegments) {
  Path p;
  p.poses = {{0, 0, 0}, {3, 4, 0}, {3, 5, 0}};
  EXPECT_DOUBLE_EQ(p.length_m(), 6.0);
}

TEST(Rng, SameSeedSameSequence) {
  Rng a(42), b(42), c(43);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.normal(), b.normal());
  EXPECT_NE(Rng(42).uniform(), c.uniform());
}

TEST(Clock, RateGateFiresAtItsRate) {
  SimClock clock(0.01);
  RateGate gate(10.0);
  int fired = 0;
  for (int i = 0; i < 100; ++i, clock.advance())
    if (gate.ready(clock.now_s())) ++fired;
  EXPECT_EQ(fired, 10);
  EXPECT_DOUBLE_EQ(clock.now_s(), 1.0);
}

TEST(Outcome, CodesAndNamesFollowMoveBaseFlex) {
  EXPECT_EQ(code(Outcome::NO_PATH_FOUND), 56);
  EXPECT_EQ(code(Outcome::BLOCKED_GOAL), 55);
  EXPECT_EQ(code(Outcome::COLLISION), 104);
  EXPECT_EQ(code(Outcome::CTRL_STOPPED), 118);
  EXPECT_EQ(code(Outcome::RECOVERY_IMPASSABLE), 158);
  EXPECT_EQ(outcome_name(Outcome::PLAN_PAT_EXCEEDED), "PAT_EXCEEDED");
  EXPECT_EQ(outcome_name(Outcome::OSCILLATION), "OSCILLATION");
}

TEST(RobotProfile, ValidateRejectsNonsense) {
  RobotProfile p;
  EXPECT_NO_THROW(p.validate());
  p.footprint_radius_m = -1.0;
  try {
    p.validate();
    FAIL() << "expected ParamError";
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("footprint_radius_m"), std::string::npos);
  }
}
