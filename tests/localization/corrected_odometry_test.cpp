#include "bipednav/localization/corrected_odometry.hpp"

#include <gtest/gtest.h>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"

namespace bipednav::localization {
namespace {

// Two walls of a corridor along x (y = +-0.4 m, 0.1 to 0.5 m high), sampled every 5 cm with 1 mm
// noise, seen from the base at T_world_base (cloud in the base frame).
PointCloud corridor_view(const SE3& T_world_base, Rng& rng) {
  PointCloud c;
  const SE3 T_base_world = T_world_base.inverse();
  for (double wall_y : {-0.4, 0.4})
    for (int i = -30; i <= 30; ++i)
      for (int k = 0; k <= 8; ++k) {
        const Eigen::Vector3d p(i * 0.05 + rng.normal(0.0, 0.001), wall_y + rng.normal(0.0, 0.001),
                                0.1 + k * 0.05 + rng.normal(0.0, 0.001));
        c.points.push_back((T_base_world * p).cast<float>());
      }
  return c;
}

TEST(CorrectedOdometry, InformationOfACorridorIsLowAlongIt) {
  Rng rng(3);
  GicpParams p;
  const GicpCloud cloud = prepare_gicp_cloud(corridor_view(SE3::Identity(), rng), p);
  const Eigen::Matrix3d H = planar_information(cloud, cloud, SE3::Identity(), Eigen::Vector3d::Zero(), 0.1);
  const double n = static_cast<double>(cloud.size());
  // Along the walls a match adds about 1 / (1 + 1); across them about 1 / (2 epsilon).
  EXPECT_LT(H(0, 0), 2.0 * n);
  EXPECT_GT(H(1, 1), 100.0 * n);
  EXPECT_EQ(planar_information(cloud, GicpCloud{}, SE3::Identity(), Eigen::Vector3d::Zero(), 0.1),
            Eigen::Matrix3d::Zero());
}

TEST(CorrectedOdometry, KeepsTheOdometryAlongACorridor) {
  Rng rng(5);
  CorrectedOdometryParams p;
  p.gicp.max_correspondence_m = 0.1;
  CorrectedOdometry co(p, SE3::Identity());
  const SE3 true1 = make_se3(0.2, 0.0, 0, 0, 0, 0);
  // The odometry over-estimates the step by 2 cm along the corridor and 1 cm across it.
  const SE3 odom1 = make_se3(0.22, 0.01, 0, 0, 0, 0);
  EXPECT_FALSE(co.update(SE3::Identity(), corridor_view(SE3::Identity(), rng)).corrected);
  const CorrectionUpdate u = co.update(odom1, corridor_view(true1, rng));
  ASSERT_TRUE(u.corrected) << u.reason;
  EXPECT_GE(u.degenerate_directions, 1);
  // Across the corridor the walls correct the estimate; along it GICP has nothing to go by and
  // the odometry stands.
  EXPECT_NEAR(u.T_corrected_base.translation().y(), 0.0, 0.003);
  EXPECT_NEAR(u.T_corrected_base.translation().x(), 0.22, 0.002);
}

TEST(CorrectedOdometry, GicpReturnsTheCorrespondencesOfItsResult) {
  // The matches gicp_align returns are each source point's nearest target point within the
  // correspondence distance at the returned pose, so the information built from them equals the
  // one built by searching again.
  Rng rng(7);
  GicpParams p;
  p.max_correspondence_m = 0.1;
  const GicpCloud target = prepare_gicp_cloud(corridor_view(SE3::Identity(), rng), p);
  const GicpCloud source = prepare_gicp_cloud(corridor_view(make_se3(0.03, 0.01, 0, 0, 0, 0.02), rng), p);
  std::vector<std::uint32_t> matches;
  const GicpResult r = gicp_align(source, target, SE3::Identity(), p, &matches);
  ASSERT_EQ(matches.size(), source.size());
  std::size_t matched = 0;
  const auto bound_sq = static_cast<float>(p.max_correspondence_m * p.max_correspondence_m);
  for (std::size_t i = 0; i < source.size(); ++i) {
    std::uint32_t j = kGicpNoMatch;
    float d2 = 0.0f;
    const Eigen::Vector3f q = (r.T_target_source * source.points[i].cast<double>()).cast<float>();
    if (!target.index.nearest(q, bound_sq, j, d2)) j = kGicpNoMatch;
    EXPECT_EQ(matches[i], j) << "source point " << i;
    matched += j != kGicpNoMatch;
  }
  EXPECT_GT(matched, source.size() / 2);
  const Eigen::Vector3d pivot(0.1, -0.2, 0.0);
  EXPECT_EQ(planar_information(source, target, r.T_target_source, pivot, matches),
            planar_information(source, target, r.T_target_source, pivot, p.max_correspondence_m));
  // Matches that do not fit the clouds are an error, not a crash.
  EXPECT_THROW(planar_information(source, target, r.T_target_source, pivot, std::vector<std::uint32_t>(3, 0)), Error);
  std::vector<std::uint32_t> bad(source.size(), kGicpNoMatch);
  bad[0] = static_cast<std::uint32_t>(target.size());
  EXPECT_THROW(planar_information(source, target, r.T_target_source, pivot, bad), Error);
}

TEST(CorrectedOdometry, RejectsABadConstrainingFraction) {
  CorrectedOdometryParams p;
  p.min_constraining_fraction = 1.5;
  EXPECT_THROW(p.validate(), Error);
}

}  // namespace
}  // namespace bipednav::localization
