#include <gtest/gtest.h>

#include "bipednav/planning/local/costmap_obstacles.hpp"
#include "local_test_utils.hpp"

namespace bipednav::planning::local {

TEST(CostmapObstacles, ClassifiesPointLineAndPolygon) {
  auto map = test::empty_costmap(0.0, 0.0, 4.0);
  map.set_cost(10, 10, mapping::kLethal);                               // single cell -> point
  for (int x = 40; x < 55; ++x) map.set_cost(x, 20, mapping::kLethal);  // 0.75 m thin wall -> line
  for (int y = 50; y < 60; ++y)
    for (int x = 50; x < 60; ++x) map.set_cost(x, y, mapping::kLethal);  // 0.5 m square -> polygon
  map.set_cost(30, 70, mapping::kInscribed);                             // inflation is ignored
  const auto obs = extract_obstacles(map, ObstacleParams{});
  ASSERT_EQ(obs.size(), 3u);
  EXPECT_EQ(obs[0].kind, Obstacle::Kind::kPoint);
  EXPECT_TRUE(obs[0].centroid.isApprox(map.geometry().cell_center(10, 10)));
  EXPECT_EQ(obs[1].kind, Obstacle::Kind::kLine);
  EXPECT_NEAR((obs[1].vertices[0] - obs[1].vertices[1]).norm(), 0.7, 1e-9);
  EXPECT_EQ(obs[2].kind, Obstacle::Kind::kPolygon);
  // The hull of the cells' corners is the 0.5 m square: distance from its centre is minus 0.25.
  const Eigen::Vector2d c = obs[2].centroid;
  EXPECT_NEAR(obstacle_distance(obs[2], c.x(), c.y()), -0.25, 1e-9);
  EXPECT_NEAR(obstacle_distance(obs[2], c.x() + 1.25, c.y()), 1.0, 1e-9);
}

TEST(CostmapObstacles, LargeClustersAreCutIntoBlocks) {
  auto map = test::empty_costmap(0.0, 0.0, 8.0);
  test::add_box(map, -3.0, -0.1, 3.0, 0.1, 0.0);  // a 6 m x 0.2 m wall
  ObstacleParams p;
  p.cluster_block_m = 1.0;
  const auto obs = extract_obstacles(map, p);
  EXPECT_GE(obs.size(), 6u);
  for (const auto& o : obs) EXPECT_LE(o.radius_m, 0.9);
}

TEST(CostmapObstacles, ConvexHullCounterClockwise) {
  const auto h = convex_hull({{0, 0}, {1, 0}, {0.5, 0.5}, {1, 1}, {0, 1}, {0.5, 0}});
  ASSERT_EQ(h.size(), 4u);
  double area = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const auto& a = h[i];
    const auto& b = h[(i + 1) % h.size()];
    area += a.x() * b.y() - b.x() * a.y();
  }
  EXPECT_NEAR(0.5 * area, 1.0, 1e-12);
}

TEST(CostmapObstacles, NearestObstaclesSortedAndLimited) {
  std::vector<Obstacle> obs(3);
  obs[0].vertices = {{3, 0}}, obs[0].centroid = {3, 0};
  obs[1].vertices = {{1, 0}}, obs[1].centroid = {1, 0};
  obs[2].vertices = {{2, 0}}, obs[2].centroid = {2, 0};
  EXPECT_EQ(nearest_obstacles(obs, {0, 0}, 2, 10.0), (std::vector<int>{1, 2}));
  EXPECT_EQ(nearest_obstacles(obs, {0, 0}, 5, 1.5), (std::vector<int>{1}));
  EXPECT_TRUE(extract_obstacles(mapping::Costmap2D{}, ObstacleParams{}).empty());
}

}  // namespace bipednav::planning::local
