#include "bipednav/planning/local/homotopy.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

namespace bipednav::planning::local {

namespace {
Obstacle point_obstacle(double x, double y) {
  Obstacle o;
  o.vertices = {{x, y}};
  o.centroid = {x, y};
  return o;
}
std::vector<Eigen::Vector2d> band_polyline_of(const TebBand& b) {
  std::vector<Eigen::Vector2d> pts;
  for (const auto& q : b.poses) pts.push_back(q.position());
  return pts;
}
std::vector<Eigen::Vector2d> centroids_of(const std::vector<Obstacle>& obs) {
  std::vector<Eigen::Vector2d> c;
  for (const auto& o : obs) c.push_back(o.centroid);
  return c;
}
}  // namespace

TEST(Homotopy, WindingSignatureSeparatesSides) {
  const std::vector<Eigen::Vector2d> c{{1, 0}};
  const auto left = winding_signature({{0, 0}, {1, 1}, {2, 0}}, c);
  const auto right = winding_signature({{0, 0}, {1, -1}, {2, 0}}, c);
  const auto left2 = winding_signature({{0, 0}, {0.5, 0.5}, {1.5, 2.0}, {2, 0}}, c);
  EXPECT_NEAR(left[0], -M_PI, 1e-9);
  EXPECT_NEAR(right[0], M_PI, 1e-9);
  EXPECT_FALSE(same_homotopy_class(left, right, 1.0));
  EXPECT_TRUE(same_homotopy_class(left, left2, 1.0));
}

TEST(Homotopy, SegmentObstacleDistance) {
  Obstacle line;
  line.vertices = {{1, -1}, {1, 1}};
  EXPECT_DOUBLE_EQ(segment_obstacle_distance({0, 0}, {2, 0}, line), 0.0);  // crossing
  EXPECT_NEAR(segment_obstacle_distance({0, 2}, {2, 2}, line), 1.0, 1e-9);
}

TEST(Homotopy, CandidatePathsAroundOneObstacleGiveTwoClasses) {
  const std::vector<Obstacle> obs{point_obstacle(2.0, 0.0)};
  const auto paths = candidate_paths({0, 0, 0}, {4, 0, 0}, obs, centroids_of(obs), 0.35, {}, 5, HomotopyParams{});
  ASSERT_EQ(paths.size(), 2u);
  // One passes left (y > 0), the other right.
  EXPECT_GT(paths[0][1].y() * paths[1][1].y(), -1e9);
  EXPECT_LT(paths[0][1].y() * paths[1][1].y(), 0.0);
}

TEST(Homotopy, BlockedSideGivesNoCandidate) {
  // An obstacle on the line and a wall of points closing its left side up to y = 3.
  std::vector<Obstacle> obs{point_obstacle(2.0, 0.0)};
  for (double y = 0.2; y <= 3.0; y += 0.2) obs.push_back(point_obstacle(2.0, y));
  HomotopyParams hp;
  hp.max_keypoint_obstacles = 20;
  const auto paths = candidate_paths({0, 0, 0}, {4, 0, 0}, obs, centroids_of(obs), 0.35, {}, 5, hp);
  ASSERT_FALSE(paths.empty());
  for (const auto& p : paths)
    for (const auto& q : p) EXPECT_LE(q.y(), 1e-9);
}

TEST(ThreadPool, RunsEveryIndexOnceAndRethrows) {
  ThreadPool pool(3);
  std::vector<int> hits(100, 0);
  pool.parallel_for(hits.size(), [&](std::size_t i) { hits[i] += 1; });
  for (int h : hits) EXPECT_EQ(h, 1);
  std::atomic<int> count{0};
  for (int rep = 0; rep < 20; ++rep) pool.parallel_for(7, [&](std::size_t) { ++count; });
  EXPECT_EQ(count.load(), 140);
  EXPECT_THROW(pool.parallel_for(4,
                                 [](std::size_t i) {
                                   if (i == 2) throw std::runtime_error("x");
                                 }),
               std::runtime_error);
}

}  // namespace bipednav::planning::local

namespace bipednav::planning::local {

TEST(HomotopyPlanner, KeepsDistinctClassesAndItsSelection) {
  TebParams p;
  HomotopyPlanner planner(p);
  const std::vector<Obstacle> obs{point_obstacle(1.5, 0.0)};
  const Pose2 start{0, 0, 0}, goal{3, 0, 0};
  const BandCandidate* first = planner.plan(start, goal, {}, {}, obs);
  ASSERT_NE(first, nullptr);
  const std::uint64_t id = first->id;
  ASSERT_EQ(planner.candidates().size(), 2u);  // left and right of the obstacle
  const std::vector<Eigen::Vector2d> c{{1.5, 0.0}};
  const auto s0 = winding_signature(band_polyline_of(planner.candidates()[0].band), c);
  const auto s1 = winding_signature(band_polyline_of(planner.candidates()[1].band), c);
  EXPECT_FALSE(same_homotopy_class(s0, s1, 1.0));
  // The symmetric alternative is no cheaper by the hysteresis margin: the selection stays.
  for (int i = 0; i < 5; ++i) {
    const BandCandidate* b = planner.plan(start, goal, {}, {}, obs);
    ASSERT_NE(b, nullptr);
    EXPECT_EQ(b->id, id);
    EXPECT_GT(b->cost.min_obstacle_dist_m, p.limits.min_obstacle_dist_m - 0.05);
  }
}

}  // namespace bipednav::planning::local
