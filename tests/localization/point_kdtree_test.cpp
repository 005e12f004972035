#include "bipednav/localization/point_kdtree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "bipednav/common/rng.hpp"

namespace bipednav::localization {
namespace {

// Points on a few planes and a sparse cloud, with exact duplicates, like a down-sampled scan.
std::vector<Eigen::Vector3f> scene(Rng& rng, int n) {
  std::vector<Eigen::Vector3f> pts;
  for (int i = 0; i < n; ++i) {
    const float u = static_cast<float>(rng.uniform(-5, 5)), v = static_cast<float>(rng.uniform(-5, 5));
    switch (i % 4) {
      case 0:
        pts.emplace_back(u, v, -1.2f);
        break;
      case 1:
        pts.emplace_back(4.0f, u, 0.5f * v);
        break;
      case 2:
        pts.emplace_back(u, v, static_cast<float>(rng.uniform(-2, 2)));
        break;
      default:
        pts.push_back(pts[static_cast<std::size_t>(rng.uniform_int(0, i - 1))]);
        break;
    }
  }
  return pts;
}

// Squared distances rounded as the tree rounds them, so bounds compare alike.
std::vector<float> brute_sq(const std::vector<Eigen::Vector3f>& pts, const Eigen::Vector3f& q) {
  std::vector<float> d;
  for (const auto& p : pts) {
    const float dx = p.x() - q.x(), dy = p.y() - q.y(), dz = p.z() - q.z();
    d.push_back(dx * dx + dy * dy + dz * dz);
  }
  return d;
}

TEST(PointKdTree, KnnMatchesBruteForce) {
  Rng rng(3);
  const auto pts = scene(rng, 3000);
  const PointKdTree tree(pts);
  std::vector<std::uint32_t> idx(20);
  std::vector<float> d2(20);
  for (int t = 0; t < 300; ++t) {
    const Eigen::Vector3f q =
        t % 2 ? pts[static_cast<std::size_t>(rng.uniform_int(0, 2999))]
              : Eigen::Vector3f(static_cast<float>(rng.uniform(-7, 7)), static_cast<float>(rng.uniform(-7, 7)),
                                static_cast<float>(rng.uniform(-3, 3)));
    std::vector<float> all = brute_sq(pts, q);
    std::sort(all.begin(), all.end());
    ASSERT_EQ(tree.knn(q, 20, idx.data(), d2.data()), 20u);
    for (std::size_t i = 0; i < 20; ++i) {
      EXPECT_FLOAT_EQ(d2[i], all[i]);
      EXPECT_FLOAT_EQ((pts[idx[i]] - q).squaredNorm(), d2[i]);
    }
    // Bounded: exactly the points closer than the bound, nearest first.
    const float bound = all[7];
    const std::size_t within = static_cast<std::size_t>(std::lower_bound(all.begin(), all.end(), bound) - all.begin());
    EXPECT_EQ(tree.knn(q, 20, idx.data(), d2.data(), bound), std::min<std::size_t>(within, 20));
    std::uint32_t j = 0;
    float dj = 0.0f;
    ASSERT_TRUE(tree.nearest(q, std::numeric_limits<float>::infinity(), j, dj));
    EXPECT_FLOAT_EQ(dj, all[0]);
    EXPECT_EQ(tree.nearest(q, all[0], j, dj), false);  // strictly closer than the bound only
  }
}

TEST(PointKdTree, TighterBoundKeepsTheSameNeighbours) {
  // A bound above the k-th nearest distance gives the same neighbours in the same order, ties
  // (exact duplicates) included: what lets LOAM bound a search by earlier neighbours' distances.
  Rng rng(5);
  const auto pts = scene(rng, 3000);
  const PointKdTree tree(pts);
  const float inf = std::numeric_limits<float>::infinity();
  for (int t = 0; t < 400; ++t) {
    const Eigen::Vector3f q =
        t % 2 ? pts[static_cast<std::size_t>(rng.uniform_int(0, 2999))]
              : Eigen::Vector3f(static_cast<float>(rng.uniform(-7, 7)), static_cast<float>(rng.uniform(-7, 7)),
                                static_cast<float>(rng.uniform(-3, 3)));
    const std::size_t k = 5;
    std::uint32_t want[k], got[k];
    float want_d[k], got_d[k];
    ASSERT_EQ(tree.knn(q, k, want, want_d), k);
    // The tightest such bound, and the largest distance of k other distinct points near q.
    std::vector<float> bounds = {std::nextafter(want_d[k - 1], inf)};
    const std::vector<float> all = brute_sq(pts, q);
    std::vector<std::size_t> order(pts.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return all[a] < all[b]; });
    std::shuffle(order.begin(), order.begin() + 30, std::mt19937(static_cast<unsigned>(t)));
    float worst = 0.0f;
    for (std::size_t i = 0; i < k; ++i) worst = std::max(worst, all[order[i]]);
    bounds.push_back(worst * 1.001f + 1e-12f);
    for (const float b : bounds) {
      ASSERT_EQ(tree.knn(q, k, got, got_d, b), k);
      for (std::size_t i = 0; i < k; ++i) {
        EXPECT_EQ(got[i], want[i]) << t << " " << i;
        EXPECT_EQ(got_d[i], want_d[i]);
      }
    }
  }
}

TEST(PointKdTree, DegenerateInputIsSafe) {
  std::uint32_t idx[5];
  float d2[5];
  std::uint32_t j = 0;
  float dj = 0.0f;
  const PointKdTree empty;
  EXPECT_EQ(empty.knn(Eigen::Vector3f::Zero(), 5, idx, d2), 0u);
  EXPECT_FALSE(empty.nearest(Eigen::Vector3f::Zero(), 1.0f, j, dj));

  // Non-finite points are never returned; fewer points than k returns them all.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const PointKdTree tree({{nan, 0, 0}, {1, 0, 0}, {0, std::numeric_limits<float>::infinity(), 0}, {2, 0, 0}});
  EXPECT_EQ(tree.indexed(), 2u);
  ASSERT_EQ(tree.knn(Eigen::Vector3f::Zero(), 5, idx, d2), 2u);
  EXPECT_EQ(idx[0], 1u);
  EXPECT_EQ(idx[1], 3u);
  EXPECT_EQ(tree.knn(Eigen::Vector3f(nan, 0, 0), 5, idx, d2), 0u);
  EXPECT_FALSE(tree.nearest(Eigen::Vector3f(nan, 0, 0), 1e9f, j, dj));

  // Many identical points: still a valid tree.
  const PointKdTree same(std::vector<Eigen::Vector3f>(1000, Eigen::Vector3f(1, 2, 3)));
  ASSERT_EQ(same.knn(Eigen::Vector3f(1, 2, 3), 5, idx, d2), 5u);
  EXPECT_EQ(d2[4], 0.0f);
}

TEST(PointKdTree, GenerationAdvancesWithEveryChangeOfTheTree) {
  const std::vector<Eigen::Vector3f> pts = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  PointKdTree tree;
  EXPECT_EQ(tree.generation(), 0u);
  tree.build(pts);
  const std::uint64_t built = tree.generation();
  EXPECT_GT(built, 0u);
  tree.build(pts);
  EXPECT_GT(tree.generation(), built);
  const std::uint64_t rebuilt = tree.generation();
  tree = PointKdTree(pts);  // a fresh tree starts over at 1: the assigned-to one does not
  EXPECT_GT(tree.generation(), rebuilt);
  EXPECT_EQ(tree.indexed(), 3u);
}

}  // namespace
}  // namespace bipednav::localization
