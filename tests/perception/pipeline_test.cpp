#include "bipednav/perception/pipeline.hpp"

#include <gtest/gtest.h>

#include "bench/synthetic_scene.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::perception {
namespace {

using bench::synthetic_digit_frame;
using bench::synthetic_digit_profile;

TEST(Pipeline, SyntheticDigitFrame) {
  const RobotProfile digit = synthetic_digit_profile();
  const SensorFrame frame = synthetic_digit_frame(digit);
  ASSERT_EQ(frame.depth.size(), 2u);
  ASSERT_TRUE(frame.lidar);
  PerceptionPipeline pipe{PerceptionParams{}};
  const PerceptionOutput out = pipe.process(frame, digit);
  EXPECT_TRUE(out.plane_from_ransac);
  EXPECT_NEAR(out.ground_plane[2], 1.0, 1e-3);
  EXPECT_NEAR(out.ground_plane[3], 0.0, 0.01);
  ASSERT_EQ(out.sources.size(), 3u);
  EXPECT_EQ(out.sources[0].name, "depth_front");
  EXPECT_EQ(out.sources[2].name, "lidar");
  EXPECT_TRUE(out.sources[2].origin_base.isApprox(Eigen::Vector3d(0, 0, 1.47)));
  EXPECT_GT(out.depth_points_in, 2 * out.depth_points_voxel);  // at least 50 % fewer points at 0.02 m
  EXPECT_EQ(out.obstacles.size(), out.obstacle_source.size());
  EXPECT_EQ(out.obstacles.frame_id, "base_link");
  // The box in front (x in [1, 1.4], up to 0.8 m) is an obstacle seen by the front camera; no
  // obstacle point lies below min_obstacle_height_m or above the robot.
  bool front_box = false;
  for (std::size_t i = 0; i < out.obstacles.size(); ++i) {
    const Eigen::Vector3f& p = out.obstacles.points[i];
    EXPECT_GE(p.z(), 0.04f);
    EXPECT_LE(p.z(), 1.61f);
    front_box |= out.obstacle_source[i] == 0 && p.x() > 0.95f && p.x() < 1.45f && p.z() > 0.1f;
  }
  EXPECT_TRUE(front_box);
  for (const auto& p : out.ground.points) EXPECT_LT(std::fabs(p.z()), 0.04f);
}

TEST(Pipeline, FallsBackToPriorWithoutGround) {
  const RobotProfile digit = synthetic_digit_profile();
  SensorFrame frame;
  frame.lidar = PointCloud{};
  for (int i = 0; i < 100; ++i) frame.lidar->points.emplace_back(2.0f, 0.01f * i, -0.5f + 0.01f * i);  // a wall
  PerceptionPipeline pipe{PerceptionParams{}};
  const PerceptionOutput out = pipe.process(frame, digit);
  EXPECT_FALSE(out.plane_from_ransac);
  EXPECT_EQ(out.ground_plane, ground_plane_z0());
  // In the base frame the wall spans z = 0.97 .. 1.96 m; only the 64 points up to the robot's 1.6 m count.
  EXPECT_EQ(out.obstacles.size(), 64u);
}

TEST(Pipeline, EmptyFrameAndErrors) {
  const RobotProfile digit = synthetic_digit_profile();
  PerceptionPipeline pipe{PerceptionParams{}};
  const PerceptionOutput out = pipe.process(SensorFrame{}, digit);
  EXPECT_FALSE(out.plane_from_ransac);
  EXPECT_TRUE(out.obstacles.empty());
  SensorFrame bad;
  bad.depth.push_back({"depth_left", PointCloud{}});
  EXPECT_THROW(pipe.process(bad, digit), Error);
  PerceptionParams p;
  p.depth_max_range_m = -1;
  EXPECT_THROW(PerceptionPipeline{p}, ParamError);
}

}  // namespace
}  // namespace bipednav::perception
