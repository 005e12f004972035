#include "bipednav/mapping/heightmap_fusion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"

using namespace bipednav::mapping;

namespace {

// Height at a world point (nullopt outside the map or when the cell is unobserved).
std::optional<float> height_at(const Heightmap& map, double x_m, double y_m) {
  const auto c = map.geometry().world_to_cell(x_m, y_m);
  if (!c || !map.known(c->x, c->y)) return std::nullopt;
  return map.height(c->x, c->y);
}

const GridGeometry kGeom{50, 50, 0.05, 0.0, 0.0};  // 2.5 x 2.5 m
const Eigen::Vector3d kSensor(1.25, -0.5, 1.5);

// One noisy point per cell at its centre: the true height plus noise with the modelled sigma.
std::vector<Eigen::Vector3f> frame(bipednav::Rng& rng, bool with_box, const HeightmapFusionParams& p) {
  std::vector<Eigen::Vector3f> pts;
  for (int y = 0; y < kGeom.height; ++y)
    for (int x = 0; x < kGeom.width; ++x) {
      const auto c = kGeom.cell_center(x, y);
      const double h = with_box && x >= 20 && x < 30 && y >= 20 && y < 30 ? 0.3 : 0.0;
      const double d = (Eigen::Vector3d(c.x(), c.y(), h) - kSensor).norm();
      pts.emplace_back(float(c.x()), float(c.y()), float(h + rng.normal(0.0, std::sqrt(p.variance_per_m2) * d)));
    }
  return pts;
}

}  // namespace

TEST(HeightmapFusion, KalmanStepFollowsEquations2And3) {
  HeightmapFusionParams p;
  float h = std::nanf(""), var = std::numeric_limits<float>::infinity();
  EXPECT_EQ(fuse_height(h, var, 0.5f, 0.01f, p), FuseResult::kInitialised);
  EXPECT_FLOAT_EQ(h, 0.5f);
  EXPECT_FLOAT_EQ(var, 0.01f);
  EXPECT_EQ(fuse_height(h, var, 0.6f, 0.03f, p), FuseResult::kFused);
  EXPECT_FLOAT_EQ(h, (0.03f * 0.5f + 0.01f * 0.6f) / 0.04f);
  EXPECT_FLOAT_EQ(var, 0.03f * 0.01f / 0.04f);
  const float h_before = h, var_before = var;
  EXPECT_EQ(fuse_height(h, var, 5.0f, 0.001f, p), FuseResult::kRejected);  // outlier
  EXPECT_FLOAT_EQ(h, h_before);
  EXPECT_FLOAT_EQ(var, var_before * 4.0f);
}

TEST(HeightmapFusion, ConvergesUnderNoiseAndRecoversAfterObjectRemoved) {
  bipednav::Rng rng(3);
  HeightmapFusionParams p;
  HeightmapFusion fusion(kGeom, p);
  for (int i = 0; i < 30; ++i) fusion.update(frame(rng, true, p), kSensor);
  const Heightmap& m = fusion.map();
  double worst = 0.0, sq = 0.0;
  for (int y = 0; y < 50; ++y)
    for (int x = 0; x < 50; ++x) {
      const double truth = x >= 20 && x < 30 && y >= 20 && y < 30 ? 0.3 : 0.0;
      worst = std::max(worst, std::abs(m.height(x, y) - truth));
      sq += (m.height(x, y) - truth) * (m.height(x, y) - truth);
      EXPECT_LT(m.variance(x, y), p.variance_per_m2 * 9.0);  // well below one observation's variance
    }
  // Single observations have sigma 0.01 * distance (up to 3.4 cm); 30 of them average it down.
  EXPECT_LT(std::sqrt(sq / 2500.0), 0.006);
  EXPECT_LT(worst, 0.04);
  EXPECT_NEAR(*height_at(m, 1.26, 1.26), 0.3, 0.02);
  // The box is removed: gate failures raise the variance until the floor is accepted again.
  for (int i = 0; i < 15; ++i) fusion.update(frame(rng, false, p), kSensor);
  worst = 0.0;
  sq = 0.0;
  for (float v : m.heights()) {
    worst = std::max(worst, double(std::abs(v)));
    sq += double(v) * v;
  }
  EXPECT_LT(std::sqrt(sq / 2500.0), 0.01);
  EXPECT_LT(worst, 0.05);
}

TEST(HeightmapFusion, TakesHighestPointIgnoresNaNOutOfMapAndFar) {
  HeightmapFusionParams p;
  p.max_range_m = 5.0;
  HeightmapFusion fusion(kGeom, p);
  const float nan = std::nanf("");
  const auto stats = fusion.update({{0.52f, 0.52f, 0.1f},
                                    {0.53f, 0.51f, 0.4f},
                                    {0.54f, 0.53f, 0.2f},
                                    {nan, 0.5f, 1.0f},
                                    {0.5f, 0.5f, nan},
                                    {-0.1f, 0.5f, 1.0f},
                                    {2.6f, 0.5f, 1.0f},
                                    {1.0f, 1.0f, -9.0f}},
                                   kSensor);
  EXPECT_EQ(stats.points_used, 3u);
  EXPECT_EQ(stats.cells_fused, 1u);
  EXPECT_FLOAT_EQ(*height_at(fusion.map(), 0.52, 0.52), 0.4f);
  EXPECT_FALSE(height_at(fusion.map(), 1.0, 1.0));
  EXPECT_FALSE(height_at(fusion.map(), -1.0, 1.0));
  EXPECT_THROW(fusion.update(std::vector<Eigen::Vector3f>{}, Eigen::Vector3d(std::nan(""), 0, 0)), bipednav::Error);
}

TEST(HeightmapFusion, FootprintMinMaxOnRotatedRectangle) {
  Heightmap m(kGeom);
  for (int y = 0; y < 50; ++y)
    for (int x = 0; x < 50; ++x) m.set(x, y, 0.01f * x, 1e-4f);
  // Axis-aligned 0.5 x 0.1 m around (1.25, 1.25): x cells 20..29.
  auto f = footprint_heights(m, {1.25, 1.25, 0.0}, 0.5, 0.1);
  EXPECT_EQ(f.cells, 20);
  EXPECT_EQ(f.known_cells, 20);
  EXPECT_FLOAT_EQ(f.min_m, 0.20f);
  EXPECT_FLOAT_EQ(f.max_m, 0.29f);
  // Rotated by 90 degrees the rectangle spans only x cells 24..25.
  f = footprint_heights(m, {1.25, 1.25, M_PI / 2}, 0.5, 0.1);
  EXPECT_EQ(f.cells, 20);
  EXPECT_FLOAT_EQ(f.min_m, 0.24f);
  EXPECT_FLOAT_EQ(f.max_m, 0.25f);
  f = footprint_heights(m, {-5.0, -5.0, 0.0}, 0.3, 0.3);
  EXPECT_EQ(f.cells, 0);
  EXPECT_TRUE(std::isnan(f.min_m));
}

TEST(HeightmapFusion, RejectsBadParams) {
  HeightmapFusionParams p;
  p.variance_growth_factor = 1.0;
  EXPECT_THROW(HeightmapFusion(kGeom, p), bipednav::ParamError);
  p = {};
  p.gate_sigma = std::nan("");
  EXPECT_THROW(HeightmapFusion(kGeom, p), bipednav::ParamError);
  EXPECT_THROW(HeightmapFusion(GridGeometry{0, 5, 0.05, 0, 0}), bipednav::ParamError);
}
