#include "bipednav/localization/gicp.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "bipednav/common/error.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/localization/corrected_odometry.hpp"
#include "bipednav/localization/drift_metrics.hpp"
#include "bipednav/perception/voxel_grid.hpp"
#include "synthetic_scene.hpp"
#include "test_data.hpp"

namespace bipednav::localization {
namespace {

double angle_of(const SE3& T) { return Eigen::AngleAxisd(T.rotation()).angle(); }

SE3 read_matrix(const std::filesystem::path& file) {
  std::ifstream in(file);
  Eigen::Matrix4d M;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) in >> M(r, c);
  EXPECT_TRUE(in) << file;
  SE3 T;
  T.matrix() = M;
  return T;
}

PointCloud downsampled(const std::filesystem::path& file) {
  perception::VoxelGridParams vp;
  vp.leaf_size_m = Eigen::Vector3d::Constant(0.2);
  return perception::voxel_downsample(io::read_pcd(file), vp);
}

TEST(Gicp, RecoversTheReferenceScanPairForwardAndSwapped) {
  BIPEDNAV_REQUIRE_DATA(target_file, "lidar/fast_gicp/251370668.pcd");
  BIPEDNAV_REQUIRE_DATA(source_file, "lidar/fast_gicp/251371071.pcd");
  BIPEDNAV_REQUIRE_DATA(relative_file, "lidar/fast_gicp/relative.txt");
  const PointCloud target = downsampled(target_file), source = downsampled(source_file);
  const SE3 truth = read_matrix(relative_file);

  const GicpResult fwd = gicp_align(source, target, SE3::Identity());
  EXPECT_TRUE(fwd.converged);
  const SE3 e1 = truth.inverse() * fwd.T_target_source;
  EXPECT_LT(e1.translation().norm(), 0.05);
  EXPECT_LT(angle_of(e1), deg2rad(1.0));
  EXPECT_GT(fwd.correspondences, source.size() / 2);
  EXPECT_LT(fwd.fitness, 0.2);

  GicpParams two;
  two.threads = 2;
  const GicpResult swapped = gicp_align(target, source, SE3::Identity(), two);
  EXPECT_TRUE(swapped.converged);
  const SE3 e2 = truth * swapped.T_target_source;  // the inverse is expected
  EXPECT_LT(e2.translation().norm(), 0.05);
  EXPECT_LT(angle_of(e2), deg2rad(1.0));
}

TEST(Gicp, ThreadCountDoesNotChangeTheResultMuch) {
  Rng rng(7);
  const auto scene = test::room_scene();
  const auto at = [](const SE3& T) { return [T](double) { return T; }; };
  const PointCloud a = test::synthetic_sweep(scene, at(make_se3(0, 0, 1.2, 0, 0, 0)), 0, {}, rng);
  const SE3 motion = make_se3(0.3, -0.1, 0.02, 0.01, -0.02, 0.15);
  const PointCloud b = test::synthetic_sweep(scene, at(make_se3(0, 0, 1.2, 0, 0, 0) * motion), 0, {}, rng);
  GicpParams p1, p2;
  p2.threads = 2;
  const GicpResult r1 = gicp_align(b, a, SE3::Identity(), p1);
  const GicpResult r2 = gicp_align(b, a, SE3::Identity(), p2);
  EXPECT_LT((motion.inverse() * r1.T_target_source).translation().norm(), 0.01);
  EXPECT_LT(angle_of(motion.inverse() * r1.T_target_source), 0.002);
  EXPECT_LT((r1.T_target_source.inverse() * r2.T_target_source).translation().norm(), 1e-4);
}

TEST(Gicp, PlaneCovarianceHasTheNormalAsItsSmallAxis) {
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) pts.emplace_back(0.1f * i, 0.1f * j, 2.0f);
  const GicpIndex index(pts);
  const auto covs = plane_covariances(index, 20, 1e-3, 1);
  const Eigen::Vector3f n = Eigen::Vector3f::UnitZ();
  EXPECT_NEAR(n.dot(covs[55] * n), 1e-3, 1e-6);
  EXPECT_NEAR(covs[55](0, 0), 1.0, 1e-5);
  EXPECT_NEAR(covs[55](1, 1), 1.0, 1e-5);
}

TEST(Gicp, BadInputIsRejected) {
  PointCloud few;
  few.points = {{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(gicp_align(few, few, SE3::Identity()), Error);
  GicpParams bad;
  bad.threads = 0;
  EXPECT_THROW(bad.validate(), ParamError);
}

TEST(Gicp, RemoveGroundDropsPointsNearTheFloor) {
  PointCloud c;
  c.points = {{1, 0, -1.2f}, {1, 0, -1.19f}, {1, 0, 0.0f}, {1, 0, std::numeric_limits<float>::quiet_NaN()}};
  const PointCloud kept = remove_ground(c, make_se3(0, 0, 1.2, 0, 0, 0), 0.05);
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_FLOAT_EQ(kept.points[0].z(), 0.0f);
}

TEST(CorrectedOdometry, RemovesTheOdometryErrorBetweenTwoClouds) {
  Rng rng(8);
  const auto scene = test::room_scene();
  const SE3 T_base_sensor = make_se3(0, 0, 1.2, 0, 0, 0);
  const auto cloud_at = [&](const SE3& T_world_base) {
    const SE3 T = T_world_base * T_base_sensor;
    return test::synthetic_sweep(
        scene, [T](double) { return T; }, 0, {}, rng);
  };
  CorrectedOdometry co(CorrectedOdometryParams{}, T_base_sensor);
  const SE3 true0 = make_se3(-1, 0, 0, 0, 0, 0), true1 = make_se3(-0.7, 0.1, 0, 0, 0, 0.1);
  // The odometry starts at the truth, then over-estimates the step by 8 cm and 2 deg.
  const SE3 odom1 = true1 * make_se3(0.08, 0.0, 0, 0, 0, deg2rad(2.0));
  EXPECT_FALSE(co.update(true0, cloud_at(true0)).corrected);
  const CorrectionUpdate u = co.update(odom1, cloud_at(true1));
  ASSERT_TRUE(u.corrected) << u.reason;
  const SE3 err = true1.inverse() * u.T_corrected_base;
  // With the floor removed and the ceiling out of view the height is unobserved: check x, y, yaw.
  EXPECT_LT(err.translation().head<2>().norm(), 0.01);
  EXPECT_LT(std::abs(matrix_to_rpy(err.rotation()).z()), deg2rad(0.2));
  EXPECT_LT(angle_of(err), deg2rad(0.5));
}

TEST(DriftMetrics, ReportsEndPointErrorsPerDistance) {
  std::vector<SE3> truth, est;
  for (int i = 0; i <= 10; ++i) {
    truth.push_back(make_se3(i, 0, 0, 0, 0, 0));
    est.push_back(make_se3(i * 1.01, 0, 0, 0, 0, deg2rad(0.1 * i)));
  }
  const Drift d = trajectory_drift(truth, est);
  EXPECT_NEAR(d.distance_m, 10.0, 1e-12);
  EXPECT_NEAR(d.translation_percent, 1.0, 1e-9);
  EXPECT_NEAR(d.yaw_deg_per_10m, 1.0, 1e-9);
  EXPECT_THROW(trajectory_drift(truth, {}), Error);
}

}  // namespace
}  // namespace bipednav::localization
