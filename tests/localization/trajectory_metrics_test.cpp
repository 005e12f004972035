#include "bipednav/localization/trajectory_metrics.hpp"

#include <gtest/gtest.h>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::localization {
namespace {

// A curved 3D trajectory: n poses along a helix-like path.
std::vector<SE3> curved_truth(std::size_t n) {
  std::vector<SE3> t;
  for (std::size_t i = 0; i < n; ++i) {
    const double s = static_cast<double>(i);
    t.push_back(make_se3(2.0 * std::sin(0.2 * s), 0.8 * s, 0.05 * s, 0.01 * s, -0.02 * s, 0.2 * s));
  }
  return t;
}

// Straight along x, 1 m per frame, heading along x.
std::vector<SE3> straight_truth(std::size_t n) {
  std::vector<SE3> t;
  for (std::size_t i = 0; i < n; ++i) t.push_back(make_se3(static_cast<double>(i), 0, 0, 0, 0, 0));
  return t;
}

TEST(TrajectoryMetrics, ARigidlyMovedTrajectoryAlignsToZeroError) {
  const std::vector<SE3> truth = curved_truth(30);
  const SE3 T = make_se3(3.0, -7.0, 1.5, 0.3, -0.2, 2.5);
  std::vector<SE3> est;
  for (const SE3& q : truth) est.push_back(T * q);
  const AbsoluteError a = absolute_trajectory_error(truth, est);
  EXPECT_NEAR(a.translation_m.rmse, 0.0, 1e-9);
  EXPECT_TRUE((a.T_truth_estimate * T).isApprox(SE3::Identity(), 1e-9));
  const RelativeError r = relative_pose_error(truth, est, 1);
  EXPECT_EQ(r.translation_m.count, 29u);
  EXPECT_NEAR(r.translation_m.max, 0.0, 1e-9);
  EXPECT_NEAR(r.rotation_deg.max, 0.0, 1e-5);
  const KittiError k = kitti_relative_error(truth, est, {{2.0, 5.0}, 1});
  EXPECT_GT(k.segments, 0u);
  EXPECT_NEAR(k.translation_percent, 0.0, 1e-7);
}

TEST(TrajectoryMetrics, AtePerpendicularOffsetsThatCancelGiveTheirSize) {
  // Offsets +-0.1 m in z, placed so that no rotation or translation reduces them.
  const std::vector<SE3> truth = straight_truth(4);
  std::vector<SE3> est = truth;
  const double dz[] = {0.1, -0.1, -0.1, 0.1};
  for (std::size_t i = 0; i < 4; ++i) est[i].translation().z() += dz[i];
  EXPECT_NEAR(absolute_trajectory_error(truth, est).translation_m.rmse, 0.1, 1e-12);
}

TEST(TrajectoryMetrics, AConstantScaleDriftGivesItsPercentage) {
  const std::vector<SE3> truth = straight_truth(20);  // 19 m
  std::vector<SE3> est;
  for (const SE3& q : truth) est.push_back(make_se3(1.01 * q.translation().x(), 0, 0, 0, 0, 0));
  EXPECT_NEAR(end_point_error_m(truth, est), 0.19, 1e-12);
  const KittiError k = kitti_relative_error(truth, est, {whole_metre_lengths(truth), 1});
  // A segment of length L ends at the first frame farther than L: L + 1 frames (metres) on, so its
  // error is 1 % of L + 1 m, divided by L as the devkit does; 19 - L first frames have one.
  double sum = 0.0, count = 0.0;
  for (int L = 1; L <= 18; ++L) {
    sum += (19 - L) * 0.01 * (L + 1) / L;
    count += 19 - L;
  }
  EXPECT_NEAR(k.translation_percent, 100.0 * sum / count, 1e-9);
  EXPECT_EQ(k.segments, 171u);
  EXPECT_NEAR(k.rotation_deg_per_m, 0.0, 1e-12);
  ASSERT_EQ(k.lengths_used_m.size(), 18u);  // 1 .. 18 m
  EXPECT_EQ(k.lengths_used_m.back(), 18.0);
  // The benchmark's 100-800 m do not fit: no segment.
  EXPECT_EQ(kitti_relative_error(truth, est).segments, 0u);
  // RPE over one frame and over 2 m: 1 % of 1 m and of 2 m.
  EXPECT_NEAR(relative_pose_error(truth, est, 1).translation_m.rmse, 0.01, 1e-12);
  const RelativeError r2 = relative_pose_error_at_distance(truth, est, 2.0);
  EXPECT_EQ(r2.translation_m.count, 18u);
  EXPECT_NEAR(r2.translation_m.mean, 0.02, 1e-12);
}

TEST(TrajectoryMetrics, KittiRotationErrorFollowsTheDevkitsSegments) {
  // Heading drifts 0.001 rad per frame; a 4 m segment ends 5 frames later (first frame farther
  // than 4 m), so each segment's rotation error is 0.005 rad over 4 m.
  const std::vector<SE3> truth = straight_truth(20);
  std::vector<SE3> est;
  for (std::size_t i = 0; i < truth.size(); ++i)
    est.push_back(make_se3(static_cast<double>(i), 0, 0, 0, 0, 0.001 * static_cast<double>(i)));
  const KittiError k = kitti_relative_error(truth, est, {{4.0}, 10});
  EXPECT_EQ(k.segments, 2u);  // first frames 0 and 10
  EXPECT_NEAR(k.rotation_deg_per_m, rad2deg(0.005 / 4.0), 1e-9);
}

TEST(TrajectoryMetrics, RejectsTrajectoriesOfDifferentLengths) {
  EXPECT_THROW(absolute_trajectory_error(straight_truth(3), straight_truth(4)), Error);
  EXPECT_THROW(end_point_error_m({}, {}), Error);
  EXPECT_THROW(kitti_relative_error(straight_truth(3), straight_truth(3), {{}, 10}), ParamError);
}

}  // namespace
}  // namespace bipednav::localization
