#include "bipednav/tracking/motion_test.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bipednav/tracking/persistent_cells.hpp"

namespace bipednav::tracking {

TEST(RegressionVelocity, ExactLineAndJitter) {
  std::vector<TimedPosition> line;
  for (int k = 0; k < 20; ++k) line.push_back({0.1 * k, {1.0 + 0.3 * 0.1 * k, 2.0 - 0.4 * 0.1 * k}});
  const WindowVelocity w = regression_velocity(line);
  EXPECT_NEAR(w.velocity.x(), 0.3, 1e-12);
  EXPECT_NEAR(w.velocity.y(), -0.4, 1e-12);
  EXPECT_NEAR(w.standard_error_mps, 0.0, 1e-9);
  EXPECT_EQ(w.samples, 20);
  EXPECT_NEAR(w.span_s, 1.9, 1e-12);
  EXPECT_TRUE(w.moving(0.15, 3.0));
  // A static object's centre jumping by +-5 cm: a slope of 0.02 m/s, well within its error.
  std::vector<TimedPosition> jitter;
  for (int k = 0; k < 20; ++k) jitter.push_back({0.1 * k, {k % 2 == 0 ? 0.05 : -0.05, 0.0}});
  const WindowVelocity j = regression_velocity(jitter);
  EXPECT_FALSE(j.moving(0.15, 3.0));
  EXPECT_GT(j.standard_error_mps, 0.01);
  // Too few samples, or all at one time: no velocity.
  EXPECT_EQ(regression_velocity(std::vector<TimedPosition>(line.begin(), line.begin() + 2)).samples, 0);
  EXPECT_EQ(regression_velocity(std::vector<TimedPosition>(3, TimedPosition{})).samples, 0);
}

TEST(PersistentCells, CellsHitForTheirSpanPersistUntilForgotten) {
  PersistentCells cells(0.1, 3.0, 1.0, 10.0);
  const std::vector<Eigen::Vector3d> post{{1.05, 1.05, 0.5}}, person{{2.05, 1.05, 1.0}};
  const auto none = [](const Eigen::Vector3d&) { return false; };
  for (int k = 0; k <= 30; ++k) cells.add(post, 0.1 * k, none);  // 3 s of hits
  EXPECT_TRUE(cells.persistent({1.02, 1.08}));
  EXPECT_FALSE(cells.persistent({1.12, 1.08}));  // the next cell
  // A run broken by gaps longer than 1 s starts over: hits at 0, 1.5, 3, 4.5 s never persist.
  PersistentCells gappy(0.1, 3.0, 1.0, 10.0);
  for (int k = 0; k < 4; ++k) gappy.add(post, 1.5 * k, none);
  EXPECT_FALSE(gappy.persistent({1.05, 1.05}));
  // Skipped points add nothing.
  PersistentCells skipping(0.1, 3.0, 1.0, 10.0);
  for (int k = 0; k <= 30; ++k) skipping.add(person, 0.1 * k, [](const Eigen::Vector3d& p) { return p.x() > 2.0; });
  EXPECT_FALSE(skipping.persistent({2.05, 1.05}));
  // Unhit for 10 s, a persistent cell is forgotten.
  cells.add({}, 12.9, none);
  EXPECT_TRUE(cells.persistent({1.05, 1.05}));
  cells.add({}, 13.1, none);
  EXPECT_FALSE(cells.persistent({1.05, 1.05}));
  cells.add({}, 14.0, none);  // the forgotten cells are dropped once a second
  EXPECT_EQ(cells.cells(), 0u);
}

}  // namespace bipednav::tracking
