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
