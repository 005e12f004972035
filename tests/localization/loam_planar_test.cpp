#include <gtest/gtest.h>

#include "bipednav/localization/loam.hpp"

using namespace bipednav;
using namespace bipednav::localization;

TEST(LoamPlanar, ProjectionKeepsXYYawAndTheAnchorsHeightAndTilt) {
  const SE3 anchor = make_se3(1.0, 2.0, 1.3, 0.02, -0.05, 0.7);
  // T = a pose 1.2 rad about the anchor's tilted frame, then disturbed in height, roll and pitch.
  const Eigen::Matrix3d tilt = rpy_to_matrix(0.0, 0.0, -0.7) * anchor.linear();
  SE3 moved = SE3::Identity();
  moved.linear() = rpy_to_matrix(0.0, 0.0, 1.2) * tilt;
  moved.translation() = Eigen::Vector3d(4.0, -1.0, 1.3);
  const SE3 p = project_to_plane(moved, anchor);
  EXPECT_TRUE(p.isApprox(moved, 1e-12));  // already level: unchanged
  SE3 disturbed = moved;
  disturbed.translation().z() = 0.8;
  disturbed.linear() = disturbed.linear() * rpy_to_matrix(0.0, 0.01, 0.0);
  const SE3 q = project_to_plane(disturbed, anchor);
  EXPECT_NEAR(q.translation().x(), 4.0, 1e-12);
  EXPECT_NEAR(q.translation().y(), -1.0, 1e-12);
  EXPECT_NEAR(q.translation().z(), 1.3, 1e-12);
  EXPECT_TRUE(q.linear().isApprox(moved.linear(), 1e-3));
  EXPECT_TRUE((q.linear() * q.linear().transpose()).isApprox(Eigen::Matrix3d::Identity(), 1e-12));
}
