#include "bipednav/perception/decimation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "bipednav/common/error.hpp"
#include "bipednav/perception/pipeline.hpp"
#include "bipednav/perception/synthetic_scene.hpp"

namespace bipednav::perception {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

TEST(Decimation, KeepsTheMedianRangePointOfEachBlock) {
  // 4 x 2 pixels: two 2 x 2 blocks. Left block: ranges 1, 2, 3, 4 -> lower median 2. Right block:
  // one finite point (kept) and three NaN.
  PointCloud in;
  in.frame_id = "cam";
  in.stamp_s = 1.5;
  in.points = {{1, 0, 0}, {4, 0, 0}, {kNan, kNan, kNan}, {kNan, kNan, kNan},
               {3, 0, 0}, {2, 0, 0}, {kNan, kNan, kNan}, {5, 1, 0}};
  PointCloud out;
  EXPECT_EQ(decimate_depth(in, 4, 2, out), 5u);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out.points[0], Eigen::Vector3f(2, 0, 0));
  EXPECT_EQ(out.points[1], Eigen::Vector3f(5, 1, 0));
  EXPECT_EQ(out.frame_id, "cam");
  EXPECT_EQ(out.stamp_s, 1.5);
  // Factor 1 keeps every finite point.
  EXPECT_EQ(decimate_depth(in, 4, 1, out), 5u);
  EXPECT_EQ(out.size(), 5u);
}

TEST(Decimation, DropsIncompleteEdgeBlocksButCountsTheirPoints) {
  PointCloud in;
  for (int i = 0; i < 15; ++i) in.points.emplace_back(1.0f + i, 0.0f, 0.0f);  // 5 x 3
  PointCloud out;
  EXPECT_EQ(decimate_depth(in, 5, 2, out), 15u);
  EXPECT_EQ(out.size(), 2u);  // blocks (0-1, 0-1) and (2-3, 0-1)
}

TEST(Decimation, BadInputIsAnError) {
  PointCloud in;
  in.points.resize(7, Eigen::Vector3f::Zero());
  PointCloud out;
  EXPECT_THROW(decimate_depth(in, 4, 2, out), Error);  // not whole rows
  EXPECT_THROW(decimate_depth(in, 0, 2, out), Error);
  EXPECT_THROW(decimate_depth(in, 7, 0, out), Error);
  EXPECT_THROW(decimate_depth(in, 7, 9, out), Error);
  PerceptionParams p;
  p.depth_decimation = 0;
  EXPECT_THROW(p.validate(), Error);
}

// Decimating the Digit frame's depth clouds by 2 keeps what the costmaps see.
TEST(Decimation, DigitFrameKeepsItsVoxels) {
  const RobotProfile digit = synthetic_digit_profile();
  const SensorFrame frame = synthetic_digit_frame(digit);
  PerceptionParams full, half;
  full.depth_decimation = 1;
  half.depth_decimation = 2;
  SensorFrame depth_only = frame;
  depth_only.lidar.reset();
  const PerceptionOutput a = PerceptionPipeline(full).process(depth_only, digit);
  const PerceptionOutput b = PerceptionPipeline(half).process(depth_only, digit);
  EXPECT_EQ(a.depth_points_in, b.depth_points_in);  // every finite point is counted either way
  EXPECT_EQ(a.depth_points_decimated, a.depth_points_in);
  EXPECT_LT(b.depth_points_decimated, a.depth_points_in / 3);
  // The 0.02 m voxel count drops by about a third (the floor far ahead, seen at a grazing angle, has
  // pixel rows more than 0.02 m apart already), but the obstacles' 2D occupancy (0.05 m cells, what
  // the costmaps see) stays within 3 %.
  EXPECT_GT(static_cast<double>(b.depth_points_voxel), 0.6 * static_cast<double>(a.depth_points_voxel));
  std::set<std::pair<int, int>> occ_a, occ_b;
  for (const auto& q : a.obstacles.points)
    occ_a.emplace(static_cast<int>(std::floor(q.x() / 0.05f)), static_cast<int>(std::floor(q.y() / 0.05f)));
  for (const auto& q : b.obstacles.points)
    occ_b.emplace(static_cast<int>(std::floor(q.x() / 0.05f)), static_cast<int>(std::floor(q.y() / 0.05f)));
  std::size_t common = 0;
  for (const auto& c : occ_a) common += occ_b.count(c);
  ASSERT_GT(occ_a.size(), 50u);
  EXPECT_GE(static_cast<double>(common), 0.97 * static_cast<double>(occ_a.size()));
  EXPECT_GE(static_cast<double>(common), 0.97 * static_cast<double>(occ_b.size()));
  std::printf("Digit depth: %zu finite, %zu decimated; voxels %zu -> %zu; obstacle cells %zu / %zu, %zu common\n",
              a.depth_points_in, b.depth_points_decimated, a.depth_points_voxel, b.depth_points_voxel, occ_a.size(),
              occ_b.size(), common);
}

}  // namespace
}  // namespace bipednav::perception
