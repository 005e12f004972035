#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bipednav/tracking/cluster_measurement.hpp"
#include "bipednav/tracking/clustering.hpp"
#include "tracking/tracking_test_utils.hpp"

namespace bipednav::tracking {

namespace {

std::vector<std::size_t> all_of(const std::vector<Eigen::Vector3d>& pts) {
  std::vector<std::size_t> idx(pts.size());
  for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = i;
  return idx;
}

// The outline of a square of side `side` centred at c, turned by yaw, a point every 1 cm, and of
// it the points a sensor at `viewpoint` sees (its faces turned towards the viewpoint).
std::vector<Eigen::Vector3d> visible_square(const Eigen::Vector2d& c, double side, double yaw,
                                            const Eigen::Vector2d& viewpoint) {
  std::vector<Eigen::Vector3d> out;
  const Eigen::Rotation2Dd R(yaw);
  for (int face = 0; face < 4; ++face) {
    const Eigen::Vector2d n = R * Eigen::Rotation2Dd(0.5 * M_PI * face) * Eigen::Vector2d::UnitX();
    const Eigen::Vector2d mid = c + 0.5 * side * n, along(-n.y(), n.x());
    if ((viewpoint - mid).dot(n) <= 0.0) continue;
    for (double s = -0.5 * side; s <= 0.5 * side + 1e-9; s += 0.01) {
      const Eigen::Vector2d p = mid + s * along;
      out.emplace_back(p.x(), p.y(), 0.4);
    }
  }
  return out;
}

}  // namespace

TEST(Clustering, PointsOfNeighbouringCellsFormOneCluster) {
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < 10; ++i) pts.emplace_back(1.0 + 0.05 * i, 1.0, 0.0);  // 1.0 .. 1.45: one
  for (int i = 0; i < 5; ++i) pts.emplace_back(2.0, 1.0 + 0.05 * i, 0.0);   // 0.55 m on: another
  pts.emplace_back(5.0, 5.0, 0.0);                                          // alone: too few
  pts.emplace_back(std::numeric_limits<double>::quiet_NaN(), 1.0, 0.0);
  pts.emplace_back(1e300, 1.0, 0.0);
  const auto clusters = euclidean_clusters(pts, 0.1, 3);
  ASSERT_EQ(clusters.size(), 2u);
  EXPECT_EQ(clusters[0], (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(clusters[1], (std::vector<std::size_t>{10, 11, 12, 13, 14}));
  EXPECT_TRUE(euclidean_clusters({}, 0.1, 1).empty());
  // Diagonal neighbours join: (0.05, 0.05) and (0.15, 0.15) lie in cells (0, 0) and (1, 1).
  const std::vector<Eigen::Vector3d> diagonal{{0.05, 0.05, 0.0}, {0.15, 0.15, 0.0}};
  EXPECT_EQ(euclidean_clusters(diagonal, 0.1, 2).size(), 1u);
}

TEST(ClusterMeasurement, CentreOfACylinderSeenFromOneSide) {
  // A 0.25 m cylinder at (3, 1) seen from the origin: its points' centroid is ~0.2 m short of
  // the centre, the measurement within 2 cm.
  TrackerParams params;
  Rng rng(1);
  test::Scan scan;
  const Eigen::Vector2d c(3.0, 1.0);
  test::scan_cylinder(scan, {0.0, 0.0}, c, 0.25, 0.5, 0.0, rng);
  std::vector<Eigen::Vector3d> pts;
  for (std::size_t i = 0; i < scan.points.size(); ++i)
    pts.emplace_back(scan.points[i].x(), scan.points[i].y(), scan.heights[i]);
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& p : pts) centroid += p.head<2>();
  centroid /= static_cast<double>(pts.size());
  EXPECT_GT((centroid - c).norm(), 0.15);
  const Detection d = measure_cluster(pts, all_of(pts), {0.0, 0.0}, params);
  EXPECT_LT((d.position - c).norm(), 0.02);
  EXPECT_NEAR(d.radius_m, 0.25, 0.02);
  EXPECT_NEAR(d.top_m, 0.5, 0.1);
  EXPECT_EQ(d.points, static_cast<int>(pts.size()));
  // Its covariance is longest along the line of sight: the unseen depth.
  const Eigen::Vector2d u = c.normalized(), w(-u.y(), u.x());
  EXPECT_GT(u.dot(d.covariance * u), 2.0 * w.dot(d.covariance * w));
}

TEST(ClusterMeasurement, CentreOfASquareFaceOnAndCornerOn) {
  TrackerParams params;
  const Eigen::Vector2d c(3.0, 0.0), eye(0.0, 0.0);
  const auto face = visible_square(c, 0.5, 0.0, eye);
  EXPECT_LT((measure_cluster(face, all_of(face), eye, params).position - c).norm(), 0.01);
  // Corner-on: the median range of the middle quarter lies behind the corner (about 0.06 m short
  // of the centre in all for a 0.5 m square).
  const auto corner = visible_square(c, 0.5, 0.25 * M_PI, eye);
  EXPECT_LT((measure_cluster(corner, all_of(corner), eye, params).position - c).norm(), 0.07);
}

}  // namespace bipednav::tracking
