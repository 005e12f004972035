#include "bipednav/perception/ground_segmentation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>

#include "bipednav/common/error.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/perception/pass_through.hpp"
#include "test_data.hpp"

namespace bipednav::perception {
namespace {

// Points on the plane n . p + d = 0 with Gaussian noise, plus uniform outliers in a box.
PointCloud noisy_plane(const Plane& plane, int n_in, int n_out, double noise, std::uint64_t seed) {
  Rng rng(seed);
  const Eigen::Vector3d n = plane.head<3>().normalized();
  const double d = plane[3] / plane.head<3>().norm();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  PointCloud c;
  for (int i = 0; i < n_in; ++i) {
    const Eigen::Vector3d p = -d * n + rng.uniform(-2, 2) * u + rng.uniform(-2, 2) * v + rng.normal(0, noise) * n;
    c.points.push_back(p.cast<float>());
  }
  for (int i = 0; i < n_out; ++i) c.points.emplace_back(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
  return c;
}

void expect_plane_near(const Plane& got, const Plane& want, double tol) {
  const Plane w = normalize_plane(want);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(got[k], w[k], tol) << "coefficient " << k << " of " << got.transpose();
  EXPECT_NEAR(got.head<3>().norm(), 1.0, 1e-9);
  EXPECT_GE(got[2], 0.0);
}

TEST(Ransac, SyntheticPlanesWithOutliers) {
  const std::vector<Plane> planes = {Plane(0, 0, 1, 0.3), Plane(0.2, -0.1, -1.0, 0.5), Plane(1, 2, 0.5, -1),
                                     Plane(1, 0, 0, 0.7)};
  for (std::size_t k = 0; k < planes.size(); ++k) {
    const PointCloud c = noisy_plane(planes[k], 3000, 2000, 0.003, 10 + k);
    Rng rng(1);
    RansacParams p;
    p.distance_threshold_m = 0.01;
    const PlaneFit fit = fit_plane_ransac(c.points, p, rng);
    ASSERT_TRUE(fit.found);
    expect_plane_near(fit.plane, planes[k], 0.005);
    EXPECT_GE(fit.inliers, 2950u);
    EXPECT_LT(fit.inliers, 3100u);  // a few outliers fall inside the slab by chance
    EXPECT_GT(fit.inlier_std_m, 0.0);
    EXPECT_LT(fit.iterations, 100);  // eq. 4.4 with u = 0.6 asks for ~19
  }
}

// RansacParams::max_points: models from every k-th point; the counts are still of all points.
TEST(Ransac, MaxPointsFitsOnASubsetAndCountsEveryPoint) {
  PointCloud c = noisy_plane(Plane(0, 0, 1, 0.02), 20000, 0, 0.003, 21);             // the floor
  const PointCloud box = noisy_plane(Plane(1, 0, 0, -1.5), 12000, 3000, 0.003, 22);  // a wall and clutter
  c.points.insert(c.points.end(), box.points.begin(), box.points.end());
  c.points.emplace_back(std::numeric_limits<float>::quiet_NaN(), 0.0f, 0.0f);
  RansacParams p;
  p.distance_threshold_m = 0.03;
  p.use_normal_prior = true;
  Rng rng_all(5), rng_sub(5);
  const PlaneFit all = fit_plane_ransac(c.points, p, rng_all);
  p.max_points = 2000;
  const PlaneFit sub = fit_plane_ransac(c.points, p, rng_sub);
  ASSERT_TRUE(all.found);
  ASSERT_TRUE(sub.found);
  expect_plane_near(sub.plane, Plane(0, 0, 1, 0.02), 0.005);
  // Counted on all 35k points, not on the ~2k of the subset.
  EXPECT_GE(sub.inliers, 19900u);
  EXPECT_NEAR(static_cast<double>(sub.inliers), static_cast<double>(all.inliers), 0.01 * all.inliers);
  EXPECT_NEAR(sub.inlier_std_m, all.inlier_std_m, 0.001);
  p.max_points = 2;
  EXPECT_THROW(p.validate(), Error);
}

TEST(Ransac, NormalPriorSelectsTheFloorOverALargerWall) {
  PointCloud c = noisy_plane(Plane(1, 0, 0, -1), 4000, 0, 0.002, 3);  // wall x = 1
  const PointCloud floor = noisy_plane(Plane(0, 0, 1, 0), 1500, 0, 0.002, 4);
  c.points.insert(c.points.end(), floor.points.begin(), floor.points.end());
  Rng rng(2);
  RansacParams p;
  p.distance_threshold_m = 0.01;
  EXPECT_NEAR(std::fabs(fit_plane_ransac(c.points, p, rng).plane[0]), 1.0, 1e-3);  // a wall: c ~ 0
  p.use_normal_prior = true;
  const PlaneFit fit = fit_plane_ransac(c.points, p, rng);
  expect_plane_near(fit.plane, Plane(0, 0, 1, 0), 0.005);
}

TEST(Ransac, SameSeedSameResult) {
  const PointCloud c = noisy_plane(Plane(0.1, 0.1, 1, 0.2), 1000, 1000, 0.01, 5);
  Rng a(9), b(9);
  const RansacParams p;
  const PlaneFit fa = fit_plane_ransac(c.points, p, a), fb = fit_plane_ransac(c.points, p, b);
  EXPECT_EQ(fa.plane, fb.plane);
  EXPECT_EQ(fa.inliers, fb.inliers);
}

TEST(Ransac, DegenerateInputs) {
  Rng rng(1);
  const RansacParams p;
  EXPECT_FALSE(fit_plane_ransac({}, p, rng).found);
  const float q = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(fit_plane_ransac({{q, q, q}, {q, 0, 0}, {0, q, 0}, {1, 1, 1}}, p, rng).found);
  EXPECT_FALSE(fit_plane_ransac({{1, 2, 3}}, p, rng).found);
  EXPECT_FALSE(fit_plane_ransac({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}, p, rng).found);  // collinear
  const PlaneFit three = fit_plane_ransac({{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}, p, rng);
  ASSERT_TRUE(three.found);
  expect_plane_near(three.plane, Plane(0, 0, 1, -1), 1e-9);
  RansacParams bad;
  bad.success_probability = 1.0;
  EXPECT_THROW(fit_plane_ransac({}, bad, rng), ParamError);
}

TEST(Ransac, LeastSquaresPlane) {
  const std::vector<Eigen::Vector3f> pts = {{0, 0, 2}, {1, 0, 2}, {0, 1, 2}, {1, 1, 2}, {5, 5, 9}};
  expect_plane_near(fit_plane_least_squares(pts, {0, 1, 2, 3}), Plane(0, 0, 1, -2), 1e-9);
  expect_plane_near(fit_plane_least_squares(pts, {0, 1}), Plane(0, 0, 1, 0), 0.0);  // too few: z = 0
}

TEST(GroundSegmentation, PclTableScene) {
  BIPEDNAV_REQUIRE_DATA(path, "pcl/table_scene_mug_stereo_textured.pcd");
  PassThroughParams band;
  band.min_height_m = 0.0;
  band.max_height_m = 1.5;
  const PointCloud c = pass_through(io::read_pcd(path), band);
  ASSERT_EQ(c.size(), 139897u);
  for (double t : {0.01, 0.03}) {
    Rng rng(1);
    RansacParams p;
    p.distance_threshold_m = t;
    const PlaneFit fit = fit_plane_ransac(c.points, p, rng);
    expect_plane_near(fit.plane, Plane(-0.0161854, 0.837724, 0.545855, -0.528787), 0.02);
    EXPECT_GT(fit.inliers, t > 0.02 ? 115000u : 60000u);
  }
}

TEST(GroundSegmentation, PclSacPlaneTest) {
  BIPEDNAV_REQUIRE_DATA(path, "pcl/sac_plane_test.pcd");
  const PointCloud c = io::read_pcd(path);
  Rng rng(1);
  RansacParams p;
  p.distance_threshold_m = 0.03;
  const PlaneFit fit = fit_plane_ransac(c.points, p, rng);
  EXPECT_GT(fit.inliers, 2000u);
  const Eigen::Vector3d by_d = fit.plane.head<3>() / fit.plane[3];
  EXPECT_NEAR(by_d.x(), -0.8964, 0.1);
  EXPECT_NEAR(by_d.y(), -0.5868, 0.1);
  EXPECT_NEAR(by_d.z(), -1.208, 0.1);
}

}  // namespace
}  // namespace bipednav::perception
