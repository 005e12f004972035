#include "bipednav/perception/decimation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "bench/synthetic_scene.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/perception/pass_through.hpp"
#include "bipednav/perception/pipeline.hpp"

namespace bipednav::perception {
namespace {

using bench::synthetic_digit_frame;
using bench::synthetic_digit_profile;

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

// The fused decimation + range limit outputs exactly what decimating and then cropping does (the
// pipeline relies on it): random organised clouds with holes, infinities, overflowing squares,
// points on the range limit, widths with and without leftover blocks, every factor path.
TEST(Decimation, WithinRangeIsDecimationThenPassThrough) {
  Rng rng(7);
  const float inf = std::numeric_limits<float>::infinity();
  for (const int width : {2, 7, 8, 13, 16, 424}) {
    for (const int factor : {1, 2, 3, 4}) {
      for (const double max_range : {0.5, 2.9, 1e30, std::numeric_limits<double>::infinity()}) {
        const int height = 6 + static_cast<int>(rng.uniform_int(0, 5));
        PointCloud in;
        for (int i = 0; i < width * height; ++i) {
          Eigen::Vector3f p(static_cast<float>(rng.uniform(-4, 4)), static_cast<float>(rng.uniform(-4, 4)),
                            static_cast<float>(rng.uniform(-4, 4)));
          const double kind = rng.uniform(0, 1);
          if (kind < 0.15)
            p.setConstant(kNan);
          else if (kind < 0.18)
            p.y() = kNan;
          else if (kind < 0.20)
            p.z() = inf;
          else if (kind < 0.22)
            p.x() = 3e19f;  // finite, but its square overflows a float
          else if (kind < 0.30)
            p = p.normalized() * static_cast<float>(max_range);  // on the limit (give or take rounding)
          in.points.push_back(p);
        }
        PointCloud decimated, expected, fused;
        const std::size_t finite = decimate_depth(in, width, factor, decimated);
        PassThroughParams range;
        range.max_range_m = max_range;
        const PassThroughTest crop(range);
        for (const auto& p : decimated.points)
          if (crop.keep(p)) expected.points.push_back(p);
        const DecimationCounts n = decimate_depth_within(in, width, factor, max_range, fused);
        SCOPED_TRACE(::testing::Message() << "width " << width << " factor " << factor << " range " << max_range);
        EXPECT_EQ(n.finite, finite);
        EXPECT_EQ(n.blocks, decimated.size());
        ASSERT_EQ(fused.size(), expected.size());
        for (std::size_t i = 0; i < fused.size(); ++i)  // bit for bit (no NaN survives)
          ASSERT_EQ(fused.points[i], expected.points[i]) << i;
      }
    }
  }
  PointCloud out;
  EXPECT_THROW(decimate_depth_within(PointCloud{}, 4, 2, 0.0, out), Error);
  EXPECT_THROW(decimate_depth_within(PointCloud{}, 4, 2, std::numeric_limits<double>::quiet_NaN(), out), Error);
}

// The four-block path picks the same medians as the one-block path (the squared ranges of both
// are x^2 + (y^2 + z^2), Eigen's squaredNorm, bit for bit): a row of 8 blocks against the same
// blocks cut into rows of one block each.
TEST(Decimation, FourBlocksAtOnceMatchOneAtATime) {
  Rng rng(3);
  PointCloud wide, narrow;
  for (int b = 0; b < 4000; ++b) {
    Eigen::Vector3f q[4];
    for (auto& p : q) {
      p = Eigen::Vector3f(static_cast<float>(rng.uniform(-3, 3)), static_cast<float>(rng.uniform(-3, 3)),
                          static_cast<float>(rng.uniform(-3, 3)));
      if (rng.uniform(0, 1) < 0.2) p.x() = kNan;
    }
    // Near ties: a permutation of one point's coordinates has the same range up to rounding.
    if (b % 3 == 0) q[1] = Eigen::Vector3f(q[0].z(), q[0].x(), q[0].y());
    narrow.points.insert(narrow.points.end(), {q[0], q[1], q[2], q[3]});
  }
  // wide: 8 blocks per row pair (16 columns); narrow: one block per row pair (2 columns).
  for (int g = 0; g < 500; ++g)
    for (int row = 0; row < 2; ++row)
      for (int k = 0; k < 8; ++k)
        for (int c = 0; c < 2; ++c)
          wide.points.push_back(narrow.points[static_cast<std::size_t>(4 * (8 * g + k) + 2 * row + c)]);
  PointCloud a, b;
  EXPECT_EQ(decimate_depth(wide, 16, 2, a), decimate_depth(narrow, 2, 2, b));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << i;
}

// Rows whose width mixes the decimation loops (8 blocks at a time with AVX2, 4 at a time, one at a
// time): the same points as one block per row pair.
TEST(Decimation, MixedBlockLoopsMatchOneAtATime) {
  Rng rng(5);
  std::vector<Eigen::Vector3f> blocks;  // 4 points per block: top-left, top-right, bottom-left, bottom-right
  for (int b = 0; b < 3000; ++b)
    for (int i = 0; i < 4; ++i) {
      Eigen::Vector3f p(static_cast<float>(rng.uniform(-3, 3)), static_cast<float>(rng.uniform(-3, 3)),
                        static_cast<float>(rng.uniform(-3, 3)));
      if (rng.uniform(0, 1) < 0.3) p.y() = kNan;
      if (b % 5 == 0 && i == 1) p = Eigen::Vector3f(blocks.back().z(), blocks.back().x(), blocks.back().y());
      blocks.push_back(p);
    }
  for (const int per_row : {13, 17, 25, 12, 4}) {  // blocks per row pair: 26, 34, 50, 24, 8 columns
    const int pairs = 3000 / per_row;
    PointCloud wide, narrow;
    for (int g = 0; g < pairs; ++g)
      for (int row = 0; row < 2; ++row)
        for (int k = 0; k < per_row; ++k)
          for (int c = 0; c < 2; ++c)
            wide.points.push_back(blocks[static_cast<std::size_t>(4 * (per_row * g + k) + 2 * row + c)]);
    narrow.points.assign(blocks.begin(), blocks.begin() + 4 * static_cast<std::ptrdiff_t>(pairs * per_row));
    PointCloud a, b;
    EXPECT_EQ(decimate_depth(wide, 2 * per_row, 2, a), decimate_depth(narrow, 2, 2, b)) << per_row;
    const DecimationCounts na = decimate_depth_within(wide, 2 * per_row, 2, 2.5, a);
    const DecimationCounts nb = decimate_depth_within(narrow, 2, 2, 2.5, b);
    EXPECT_EQ(na.finite, nb.finite);
    EXPECT_EQ(na.blocks, nb.blocks);
    ASSERT_EQ(a.size(), b.size()) << per_row;
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << per_row << " " << i;
  }
}

// The pipeline voxelises the fused output without a crop; on the Digit frame's depth clouds the
// voxels are bit for bit those of decimating, then voxelising with the range crop (the crop's
// dropped points only split runs of the voxel sums, whose double sums of floats are exact).
TEST(Decimation, DigitFrameVoxelsMatchTheCroppedPath) {
  const RobotProfile digit = synthetic_digit_profile();
  const SensorFrame frame = synthetic_digit_frame(digit);
  ASSERT_FALSE(frame.depth.empty());
  const PerceptionParams params;
  for (const DepthCloud& d : frame.depth) {
    PointCloud decimated, within, old_voxels, new_voxels;
    VoxelGrid grid(params.depth_voxel);
    decimate_depth(d.cloud, params.depth_image_width, params.depth_decimation, decimated);
    PassThroughParams range;
    range.max_range_m = params.depth_max_range_m;
    const PassThroughTest crop(range);
    grid.filter(decimated, old_voxels, &crop);
    decimate_depth_within(d.cloud, params.depth_image_width, params.depth_decimation, params.depth_max_range_m, within);
    EXPECT_LT(within.size(), decimated.size());
    grid.filter(within, new_voxels);
    ASSERT_GT(new_voxels.size(), 100u);
    ASSERT_EQ(new_voxels.size(), old_voxels.size());
    for (std::size_t i = 0; i < new_voxels.size(); ++i) ASSERT_EQ(new_voxels.points[i], old_voxels.points[i]) << i;
  }
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
