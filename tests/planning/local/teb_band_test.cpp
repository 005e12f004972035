#include "bipednav/planning/local/teb_band.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace bipednav::planning::local {

TEST(TebBand, InitAlongViaPoints) {
  TebLimits lim;
  TebBandParams bp;
  const auto band = init_band({0, 0, 0}, {Eigen::Vector2d(1.0, 0.0)}, {1.0, 1.0, 1.57}, lim, bp);
  // 2 m path, step 0.15 m (0.5 m/s * 0.3 s) -> 14 intervals.
  ASSERT_EQ(band.size(), 15u);
  ASSERT_EQ(band.dt_s.size(), 14u);
  EXPECT_NEAR(band.dt_s[0], (2.0 / 14) / 0.5, 1e-9);
  EXPECT_DOUBLE_EQ(band.poses.back().theta, 1.57);
  EXPECT_NEAR(band.poses[3].theta, 0.0, 1e-9);        // on the first leg
  EXPECT_NEAR(band.poses[10].theta, M_PI / 2, 1e-9);  // on the second leg
  EXPECT_NEAR(band.duration_s(), 4.0, 1e-9);
  const Path p = band.to_path();
  EXPECT_NEAR(p.times_s.back(), 4.0, 1e-9);
}

TEST(TebBand, InitRotationInPlaceTakesTurningTime) {
  const auto band = init_band({0, 0, 0}, {}, {0, 0, 1.6}, TebLimits{}, TebBandParams{});
  EXPECT_GE(band.size(), 3u);
  EXPECT_NEAR(band.duration_s(), 1.6 / 0.8, 1e-9);
}

TEST(TebBand, ResampleKeepsDtNearReferenceWithoutOscillation) {
  TebBandParams bp;  // dt_ref 0.3, hysteresis 0.1
  TebBand band;
  for (int i = 0; i < 5; ++i) band.poses.push_back({0.5 * i, 0, 0});
  band.dt_s = {1.0, 0.05, 0.05, 0.3};
  EXPECT_TRUE(resample_band(band, bp));
  for (double dt : band.dt_s) {
    EXPECT_LE(dt, bp.dt_ref_s + bp.dt_hysteresis_s + 1e-12);
  }
  const std::size_t n = band.size();
  EXPECT_NEAR(band.duration_s(), 1.4, 1e-12);  // total time preserved
  // Stable: no further change, repeatedly.
  for (int i = 0; i < 5; ++i) EXPECT_FALSE(resample_band(band, bp));
  EXPECT_EQ(band.size(), n);
}

TEST(TebBand, ResampleRespectsMinAndMaxSamples) {
  TebBandParams bp;
  bp.min_samples = 3;
  bp.max_samples = 6;
  TebBand band;
  for (int i = 0; i < 3; ++i) band.poses.push_back({1.0 * i, 0, 0});
  band.dt_s = {5.0, 5.0};
  resample_band(band, bp);
  EXPECT_EQ(band.size(), 6u);
  TebBand small;
  for (int i = 0; i < 3; ++i) small.poses.push_back({0.01 * i, 0, 0});
  small.dt_s = {0.01, 0.01};
  resample_band(small, bp);
  EXPECT_EQ(small.size(), 3u);
}

TEST(TebBand, WarmStartPrunesPassedPoses) {
  auto band = init_band({0, 0, 0}, {}, {3, 0, 0}, TebLimits{}, TebBandParams{});
  const std::size_t n = band.size();
  ASSERT_TRUE(warm_start_band(band, {0.46, 0.01, 0.0}, {3.1, 0, 0}, TebBandParams{}));
  EXPECT_EQ(band.size(), n - 3);  // poses at 0, 0.15, 0.3 passed; 0.45 became the start
  EXPECT_DOUBLE_EQ(band.poses.front().x, 0.46);
  EXPECT_DOUBLE_EQ(band.poses.back().x, 3.1);
  EXPECT_EQ(band.dt_s.size(), band.size() - 1);
  // A goal jump beyond reinit_goal_dist_m asks for re-initialisation.
  EXPECT_FALSE(warm_start_band(band, {0.5, 0, 0}, {3.1, 2.0, 0}, TebBandParams{}));
}

}  // namespace bipednav::planning::local
