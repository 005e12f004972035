#include "bipednav/planning/local/teb_terms.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace bipednav::planning::local {

constexpr double kPi = std::numbers::pi;

TEST(TebTerms, NonholonomicZeroOnCommonArc) {
  // Two poses on a circle of radius 2 around the origin with tangent headings (eq. 5.5).
  const double r = 2.0, a1 = 0.1, a2 = 0.5;
  const double e = nonholonomic_error(r * std::cos(a1), r * std::sin(a1), a1 + kPi / 2, r * std::cos(a2),
                                      r * std::sin(a2), a2 + kPi / 2);
  EXPECT_NEAR(e, 0.0, 1e-12);
  // Straight ahead, same heading: zero; sideways step: |h| = 2 * step.
  EXPECT_NEAR(nonholonomic_error(0.0, 0.0, 0.0, 1.0, 0.0, 0.0), 0.0, 1e-12);
  EXPECT_NEAR(nonholonomic_error(0.0, 0.0, 0.0, 0.0, 0.3, 0.0), 0.6, 1e-12);
}

TEST(TebTerms, SmoothSignApproximatesSign) {
  EXPECT_DOUBLE_EQ(smooth_sign(0.0, 100.0), 0.0);
  EXPECT_NEAR(smooth_sign(1.0, 100.0), 100.0 / 101.0, 1e-12);
  EXPECT_NEAR(smooth_sign(-1.0, 100.0), -100.0 / 101.0, 1e-12);
  EXPECT_LT(std::abs(smooth_sign(-1e9, 100.0)), 1.0);
}

TEST(TebTerms, LinearAndAngularVelocity) {
  // 0.5 m forward in 1 s: v = 0.5 * (50 / 51) with the smooth sign of eq. 5.10.
  EXPECT_NEAR(linear_velocity(0.0, 0.0, 0.0, 0.5, 0.0, 1.0, 100.0), 0.5 * 50.0 / 51.0, 1e-9);
  EXPECT_NEAR(linear_velocity(0.0, 0.0, 0.0, -0.5, 0.0, 1.0, 100.0), -0.5 * 50.0 / 51.0, 1e-9);
  EXPECT_NEAR(exact_linear_velocity(0.0, 0.0, 0.0, -0.5, 0.0, 0.5), -1.0, 1e-12);
  // Angular velocity wraps through +-pi.
  EXPECT_NEAR(angular_velocity(3.0, -3.0, 0.5), (2 * kPi - 6.0) / 0.5, 1e-9);
  EXPECT_NEAR(angular_velocity(0.0, 0.4, 2.0), 0.2, 1e-12);
}

TEST(TebTerms, Acceleration) {
  EXPECT_DOUBLE_EQ(acceleration(0.2, 0.4, 0.1, 0.3), 1.0);  // 2 * 0.2 / 0.4
  EXPECT_DOUBLE_EQ(acceleration(0.4, 0.4, 0.1, 0.3), 0.0);
}

TEST(TebTerms, PenaltiesWithEpsilonMargin) {
  // eq. 5.17: zero inside [-(a - eps), a - eps], linear outside.
  EXPECT_DOUBLE_EQ(penalty_symmetric(0.3, 0.5, 0.1), 0.0);
  EXPECT_NEAR(penalty_symmetric(0.6, 0.5, 0.1), 0.2, 1e-12);
  EXPECT_NEAR(penalty_symmetric(-0.6, 0.5, 0.1), 0.2, 1e-12);
  // Asymmetric forward/backward velocity limits.
  EXPECT_NEAR(penalty_interval(-0.3, -0.2, 0.5, 0.0), 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(penalty_interval(0.4, -0.2, 0.5, 0.0), 0.0);
  // eq. 5.19: separation below rho_min + eps.
  EXPECT_NEAR(penalty_below(0.3, 0.35, 0.05), 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(penalty_below(0.5, 0.35, 0.05), 0.0);
}

TEST(TebTerms, BackwardsTimeAndViaPoint) {
  EXPECT_DOUBLE_EQ(backwards_error(0.0, 0.0, 0.0, 0.3, 0.0), 0.0);
  EXPECT_NEAR(backwards_error(0.0, 0.0, 0.0, -0.3, 0.0), 0.3, 1e-12);
  EXPECT_DOUBLE_EQ(time_error(0.25), 0.25);
  const auto e = via_point_error(1.0, 2.0, Eigen::Vector2d(0.5, 2.5));
  EXPECT_DOUBLE_EQ(e.squaredNorm(), 0.5);
}

TEST(TebTerms, ObstacleDistances) {
  EXPECT_NEAR(distance_to_point(3.0, 4.0, Eigen::Vector2d(0, 0)), 5.0, 1e-9);
  const Eigen::Vector2d a(0, 0), b(2, 0);
  EXPECT_NEAR(distance_to_segment(1.0, 1.5, a, b), 1.5, 1e-9);
  EXPECT_NEAR(distance_to_segment(3.0, 0.0, a, b), 1.0, 1e-9);
  const std::vector<Eigen::Vector2d> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_NEAR(distance_to_polygon(2.0, 0.5, square), 1.0, 1e-9);
  EXPECT_NEAR(distance_to_polygon(0.5, 0.4, square), -0.4, 1e-9);  // inside: minus the depth
}

// The double polygon distance takes one square root (of the nearest edge's square): it must give bitwise the
// generic (per-edge root) value, which the Jets' values and the optimiser's cost evaluations follow.
TEST(TebTerms, PolygonDistanceOneRootMatchesPerEdgeRoots) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int t = 0; t < 2000; ++t) {
    const int k = 3 + static_cast<int>(rng() % 10);
    const Eigen::Vector2d c(10 * u(rng), 10 * u(rng));
    const double r = 0.02 + std::abs(u(rng));
    std::vector<Eigen::Vector2d> v;
    for (int i = 0; i < k; ++i) {
      const double a = 2 * kPi * i / k + 0.1 * u(rng);
      v.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
    }
    if (t % 10 == 0) v[1] = v[0];  // a degenerate edge
    for (int q = 0; q < 8; ++q) {
      const double px = q == 0 ? v[0].x() : c.x() + 2 * r * u(rng), py = q == 0 ? v[0].y() : c.y() + 2 * r * u(rng);
      bool inside = true;
      double best = distance_to_segment(px, py, v.back(), v.front());
      for (std::size_t i = 0; i < v.size(); ++i) {
        const Eigen::Vector2d& a = v[i];
        const Eigen::Vector2d& b = v[(i + 1) % v.size()];
        EXPECT_EQ(std::sqrt(squared_distance_to_segment(px, py, a, b)), distance_to_segment(px, py, a, b));
        if ((b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x()) < 0.0) inside = false;
        if (i + 1 < v.size()) best = std::min(best, distance_to_segment(px, py, a, b));
      }
      EXPECT_EQ(distance_to_polygon(px, py, v), inside ? -best : best);
    }
  }
}

}  // namespace bipednav::planning::local
