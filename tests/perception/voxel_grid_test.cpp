#include "bipednav/perception/voxel_grid.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "bipednav/common/error.hpp"

namespace bipednav::perception {
namespace {

VoxelGridParams leaf(double x, double y, double z) {
  VoxelGridParams p;
  p.leaf_size_m = Eigen::Vector3d(x, y, z);
  return p;
}

TEST(VoxelGrid, ExactCentroidsInOrderOfFirstAppearance) {
  PointCloud c;
  c.frame_id = "cam";
  c.stamp_s = 3.5;
  // Voxel (1, 0, 0) gets points 0 and 2, voxel (0, 0, 0) points 1 and 3, voxel (-1, 0, 0) point 4.
  c.points = {
      {1.25f, 0.25f, 0.5f}, {0.25f, 0.5f, 0.75f}, {1.75f, 0.75f, 0.25f}, {0.75f, 0.0f, 0.25f}, {-0.5f, 0.5f, 0.5f}};
  c.intensities = {1.0f, 2.0f, 3.0f, 4.0f, 5.0f};
  c.time_offsets_s = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f};
  c.rings = {7, 8, 9, 10, 11};
  const PointCloud v = voxel_downsample(c, leaf(1.0, 1.0, 1.0));
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v.points[0], Eigen::Vector3f(1.5f, 0.5f, 0.375f));
  EXPECT_EQ(v.points[1], Eigen::Vector3f(0.5f, 0.25f, 0.5f));
  EXPECT_EQ(v.points[2], Eigen::Vector3f(-0.5f, 0.5f, 0.5f));
  EXPECT_EQ(v.intensities, (std::vector<float>{2.0f, 3.0f, 5.0f}));
  EXPECT_EQ(v.time_offsets_s, (std::vector<float>{0.25f, 0.5f, 1.0f}));
  EXPECT_EQ(v.rings, (std::vector<std::uint16_t>{7, 8, 11}));
  EXPECT_EQ(v.frame_id, "cam");
  EXPECT_EQ(v.stamp_s, 3.5);
}

TEST(VoxelGrid, LeafSizePerAxis) {
  PointCloud c;
  c.points = {{0.1f, 0.1f, 0.1f}, {0.9f, 0.1f, 0.1f}, {0.1f, 0.3f, 0.1f}, {0.1f, 0.1f, 2.9f}};
  // x leaf 1: first two merge; y leaf 0.25 splits the third off; z leaf 3 keeps the last in voxel 0.
  const PointCloud v = voxel_downsample(c, leaf(1.0, 0.25, 3.0));
  ASSERT_EQ(v.size(), 2u);
  EXPECT_NEAR(v.points[0].x(), (0.1f + 0.9f + 0.1f) / 3.0f, 1e-6);
  EXPECT_NEAR(v.points[0].z(), (0.1f + 0.1f + 2.9f) / 3.0f, 1e-6);
  EXPECT_EQ(v.points[1], Eigen::Vector3f(0.1f, 0.3f, 0.1f));
}

TEST(VoxelGrid, NegativeCoordinatesUseFloor) {
  PointCloud c;
  c.points = {{-0.01f, 0.0f, 0.0f}, {0.01f, 0.0f, 0.0f}};
  EXPECT_EQ(voxel_downsample(c, leaf(0.02, 0.02, 0.02)).size(), 2u);
}

TEST(VoxelGrid, EmptyNanOnlyAndSinglePoint) {
  EXPECT_TRUE(voxel_downsample(PointCloud{}, VoxelGridParams{}).empty());
  PointCloud nan;
  const float q = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  nan.points = {{q, q, q}, {q, 0.0f, 0.0f}, {inf, 0.0f, 0.0f}};
  EXPECT_TRUE(voxel_downsample(nan, VoxelGridParams{}).empty());
  PointCloud one;
  one.points = {{1.0f, -2.0f, 3.0f}};
  const PointCloud v = voxel_downsample(one, VoxelGridParams{});
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v.points[0], one.points[0]);
}

TEST(VoxelGrid, RejectsBadParamsAndOverflow) {
  EXPECT_THROW(voxel_downsample(PointCloud{}, leaf(0.0, 1.0, 1.0)), ParamError);
  EXPECT_THROW(voxel_downsample(PointCloud{}, leaf(1.0, std::nan(""), 1.0)), ParamError);
  PointCloud far;
  far.points = {{1e5f, 0.0f, 0.0f}};
  EXPECT_THROW(voxel_downsample(far, leaf(0.02, 0.02, 0.02)), Error);
  PointCloud bad;
  bad.points = {{0.0f, 0.0f, 0.0f}};
  bad.rings = {1, 2};
  EXPECT_THROW(voxel_downsample(bad, VoxelGridParams{}), Error);
}

TEST(VoxelGrid, DenseGridReducesToOnePointPerVoxel) {
  PointCloud c;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) c.points.emplace_back(0.005f * i + 0.0025f, 0.005f * j + 0.0025f, 0.001f);
  const PointCloud v = voxel_downsample(c, leaf(0.02, 0.02, 0.02));
  EXPECT_EQ(v.size(), 100u);  // 0.2 x 0.2 m in 0.02 m voxels
}

}  // namespace
}  // namespace bipednav::perception

namespace bipednav::perception {
namespace {

TEST(VoxelGridClass, ReusedBetweenCallsAndCropped) {
  VoxelGrid grid(VoxelGridParams{});
  PointCloud a, b, out;
  for (int i = 0; i < 5000; ++i) a.points.emplace_back(0.01f * i, 0.0f, 0.0f);  // 50 m line, 2500 voxels
  b.points = {{0.001f, 0.001f, 0.001f}, {0.003f, 0.003f, 0.003f}, {5.0f, 0.0f, 0.0f}};
  grid.filter(a, out);
  EXPECT_EQ(out.size(), 2500u);
  grid.filter(b, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_TRUE(out.points[0].isApprox(Eigen::Vector3f(0.002f, 0.002f, 0.002f)));
  PassThroughParams range;
  range.max_range_m = 1.0;
  const PassThroughTest crop(range);
  grid.filter(b, out, &crop);
  EXPECT_EQ(out.size(), 1u);
  EXPECT_THROW(grid.filter(out, out), Error);
}

}  // namespace
}  // namespace bipednav::perception

#include <cmath>
#include <map>
#include <random>
#include <tuple>

namespace bipednav::perception {
namespace {

// The definition, written plainly: voxel = floor(p * (1 / leaf)) per axis with the product in
// double, voxels in order of their first point, centroids of double sums, the first point's ring.
PointCloud reference_voxels(const PointCloud& in, const Eigen::Vector3d& leaf, const PassThroughTest* crop) {
  const Eigen::Vector3d inv = leaf.cwiseInverse();
  std::map<std::tuple<double, double, double>, std::size_t> index;
  std::vector<std::array<double, 6>> sums;  // x, y, z, intensity, time, count
  std::vector<std::size_t> first;
  for (std::size_t i = 0; i < in.size(); ++i) {
    const Eigen::Vector3f& p = in.points[i];
    if (!p.allFinite() || (crop && !crop->keep(p))) continue;
    const auto cell =
        std::make_tuple(std::floor(p.x() * inv.x()), std::floor(p.y() * inv.y()), std::floor(p.z() * inv.z()));
    const auto [it, fresh] = index.try_emplace(cell, sums.size());
    if (fresh) {
      sums.push_back({});
      first.push_back(i);
    }
    auto& s = sums[it->second];
    s[0] += p.x();
    s[1] += p.y();
    s[2] += p.z();
    s[3] += in.has_intensity() ? in.intensities[i] : 0.0f;
    s[4] += in.has_time() ? in.time_offsets_s[i] : 0.0f;
    s[5] += 1.0;
  }
  PointCloud out;
  for (std::size_t v = 0; v < sums.size(); ++v) {
    const auto& s = sums[v];
    out.points.emplace_back(static_cast<float>(s[0] / s[5]), static_cast<float>(s[1] / s[5]),
                            static_cast<float>(s[2] / s[5]));
    if (in.has_intensity()) out.intensities.push_back(static_cast<float>(s[3] / s[5]));
    if (in.has_time()) out.time_offsets_s.push_back(static_cast<float>(s[4] / s[5]));
    if (in.has_ring()) out.rings.push_back(in.rings[first[v]]);
  }
  return out;
}

// Random clouds around block and SIMD-width boundaries, with NaN, infinities, repeated points (runs
// of one voxel), negative coordinates and points on voxel faces; optional fields and a range crop.
TEST(VoxelGrid, MatchesTheDefinitionOnRandomClouds) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  PassThroughParams range;
  range.max_range_m = 1.5;
  const PassThroughTest crop(range);
  VoxelGrid reused(leaf(0.05, 0.03, 0.02));
  const std::size_t sizes[] = {1, 2, 3, 4, 5, 7, 255, 256, 257, 511, 1000, 4099};
  for (std::size_t trial = 0; trial < 36; ++trial) {
    const std::size_t n = sizes[trial % 12];
    const float scale = trial % 3 == 0 ? 0.1f : 2.0f;
    PointCloud c;
    for (std::size_t i = 0; i < n; ++i) {
      Eigen::Vector3f p(u(rng) * scale, u(rng) * scale, u(rng) * scale);
      if (rng() % 8 == 0 && i > 0) p = c.points.back() + Eigen::Vector3f::Constant(1e-4f);
      if (rng() % 17 == 0) p[rng() % 3] = nan;
      if (rng() % 29 == 0) p[rng() % 3] = rng() % 2 ? inf : -inf;
      if (rng() % 13 == 0) p.x() = 0.05f * static_cast<float>(static_cast<int>(rng() % 9) - 4);  // on a face
      c.points.push_back(p);
      c.intensities.push_back(u(rng));
      c.time_offsets_s.push_back(u(rng));
      c.rings.push_back(static_cast<std::uint16_t>(rng() % 16));
    }
    if (trial % 2) c.intensities.clear();
    if (trial % 4 == 1) c.time_offsets_s.clear();
    if (trial % 5 == 2) c.rings.clear();
    const PassThroughTest* cr = trial % 3 == 1 ? &crop : nullptr;
    const PointCloud want = reference_voxels(c, Eigen::Vector3d(0.05, 0.03, 0.02), cr);
    PointCloud got;
    reused.filter(c, got, cr);
    SCOPED_TRACE("trial " + std::to_string(trial) + ", " + std::to_string(n) + " points");
    EXPECT_EQ(got.points, want.points);
    EXPECT_EQ(got.intensities, want.intensities);
    EXPECT_EQ(got.time_offsets_s, want.time_offsets_s);
    EXPECT_EQ(got.rings, want.rings);
  }
}

// The vectorised keys agree with floor() at voxel faces, just inside them, at the ends of the key
// range, and drop non-finite points without reporting an overflow.
TEST(VoxelGrid, KeysAtFacesAndRangeEnds) {
  const double half = 1 << 20;
  const float below_one = std::nextafter(1.0f, 0.0f), above_m1 = std::nextafter(-1.0f, 0.0f);
  const std::vector<float> values = {0.0f,
                                     -0.0f,
                                     1.0f,
                                     -1.0f,
                                     below_one,
                                     above_m1,
                                     0.5f,
                                     -0.5f,
                                     static_cast<float>(-half),
                                     std::nextafter(static_cast<float>(half), 0.0f)};
  std::vector<float> xyz;
  for (std::size_t a = 0; a < values.size(); ++a)
    for (std::size_t b = 0; b < values.size(); ++b)
      xyz.insert(xyz.end(), {values[a], values[b], values[(a + b) % values.size()]});
  const std::size_t n = xyz.size() / 3;
  std::vector<std::uint64_t> keys(n);
  ASSERT_TRUE(detail::voxel_keys(xyz.data(), n, Eigen::Vector3d::Ones(), keys.data()));
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t want = 0;
    for (int a = 0; a < 3; ++a)
      want = (want << 21) | static_cast<std::uint64_t>(std::floor(static_cast<double>(xyz[3 * i + a])) + half);
    EXPECT_EQ(keys[i], want) << "point " << i;
  }
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::vector<float> odd = {nan, 0, 0, 0, inf, 0, 0, 0, -inf, 1, 2, 3, 4, 5, nan};
  std::vector<std::uint64_t> k5(5);
  EXPECT_TRUE(detail::voxel_keys(odd.data(), 5, Eigen::Vector3d::Ones(), k5.data()));
  EXPECT_EQ(k5[0], detail::kSkipKey);
  EXPECT_EQ(k5[1], detail::kSkipKey);
  EXPECT_EQ(k5[2], detail::kSkipKey);
  EXPECT_NE(k5[3], detail::kSkipKey);
  EXPECT_EQ(k5[4], detail::kSkipKey);
  std::vector<float> far = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, static_cast<float>(half)};
  EXPECT_FALSE(detail::voxel_keys(far.data(), 5, Eigen::Vector3d::Ones(), k5.data()));
  EXPECT_FALSE(detail::voxel_keys(far.data() + 3, 4, Eigen::Vector3d::Ones(), k5.data()));
}

TEST(VoxelGridClass, FarPointsAreAnErrorOnlyWhenKept) {
  PointCloud c;
  for (int i = 0; i < 9; ++i) c.points.emplace_back(0.01f * i + 0.005f, 0.0f, 0.0f);  // 5 voxels
  c.points.emplace_back(1e5f, 0.0f, 0.0f);                                            // beyond 2^20 voxels of 0.02 m
  PassThroughParams range;
  range.max_range_m = 2.9;
  const PassThroughTest crop(range);
  VoxelGrid grid;
  PointCloud out;
  EXPECT_NO_THROW(grid.filter(c, out, &crop));
  EXPECT_EQ(out.size(), 5u);
  EXPECT_THROW(grid.filter(c, out), Error);
}

}  // namespace
}  // namespace bipednav::perception
