#include "bipednav/planning/local/costmap_obstacles.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

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

// make_obstacle builds the hull from each row's end cells only: the vertices must be those of the hull of
// every cell's corners, bit for bit, for blobs in scan order and shuffled.
TEST(CostmapObstacles, PolygonFromRowEndsMatchesAllCorners) {
  auto map = test::empty_costmap(-3.3, 1.7, 4.0);
  const auto& g = map.geometry();
  const double half = 0.5 * g.resolution_m;
  std::mt19937 rng(7);
  int polygons = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Eigen::Vector2d> pts;
    const int cx = 20 + static_cast<int>(rng() % 30), cy = 20 + static_cast<int>(rng() % 30);
    const int w = 2 + static_cast<int>(rng() % 18), h = 2 + static_cast<int>(rng() % 18);
    for (int y = cy; y < cy + h; ++y) {
      // ragged rows (some with holes), so the row ends move and the hull has slanted edges
      const int x0 = cx + static_cast<int>(rng() % 4), x1 = cx + w - static_cast<int>(rng() % 4);
      for (int x = x0; x <= x1; ++x) {
        if (x != x0 && x != x1 && rng() % 5 == 0) continue;
        pts.push_back(g.cell_center(x, y));
      }
    }
    std::vector<Eigen::Vector2d> corners;
    for (const auto& p : pts) {
      for (const double sx : {-half, half})
        for (const double sy : {-half, half}) corners.emplace_back(p.x() + sx, p.y() + sy);
    }
    const auto expected = convex_hull(corners);
    auto shuffled = pts;
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    for (const auto* input : {&pts, &shuffled}) {
      const Obstacle o = make_obstacle(*input, half, ObstacleParams{});
      if (o.kind != Obstacle::Kind::kPolygon) continue;
      ++polygons;
      ASSERT_EQ(o.vertices.size(), expected.size());
      for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(o.vertices[i].x(), expected[i].x());
        EXPECT_EQ(o.vertices[i].y(), expected[i].y());
      }
    }
  }
  EXPECT_GT(polygons, 300);
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
