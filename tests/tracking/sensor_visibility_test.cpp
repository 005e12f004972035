#include "bipednav/tracking/sensor_visibility.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"
#include "tracking/tracking_test_utils.hpp"

namespace bipednav::tracking {

using test::digit_sensors;
using test::digit_visibility;

TEST(SensorVisibility, VisibilityOfKnownPointsFromDigitsSensors) {
  const SensorVisibility vis = digit_visibility();
  // The LiDAR's lowest ring (-15 deg from 1.474 m) reaches a 0.5 m top at 0.974 / tan(15 deg) =
  // 3.635 m: beside the robot (outside both cameras) a 0.5 m cube is seen only beyond that.
  EXPECT_FALSE(vis.sees_base_point({0.0, 3.60, 0.5}));
  EXPECT_TRUE(vis.sees_base_point({0.0, 3.67, 0.5}));
  EXPECT_FALSE(vis.sees_base_point({0.0, 2.0, 0.5}));
  EXPECT_FALSE(vis.sees_base_point({0.0, -2.0, 0.3}));
  // Forward camera: 1.0 m ahead at 0.3 m is 35.8 deg below its horizon (axis at 45, half vfov 29).
  EXPECT_TRUE(vis.sees_base_point({1.0, 0.0, 0.3}));
  // 3 m ahead, 0.5 m high: 8.8 deg below the horizon (above the frustum) and 2.93 m from the
  // camera (beyond its 2.9 m range); too low for the LiDAR (-18 deg).
  EXPECT_FALSE(vis.sees_base_point({3.0, 0.0, 0.5}));
  // Backward camera, mirrored.
  EXPECT_TRUE(vis.sees_base_point({-1.2, 0.0, 0.3}));
  // Above the robot's head the LiDAR sees within +-15 deg only.
  EXPECT_TRUE(vis.sees_base_point({2.0, 0.0, 1.474}));
  EXPECT_FALSE(vis.sees_base_point({0.5, 0.0, 1.474 + 0.5}));
  // In the map frame: the robot at (10, 5) facing +y.
  const Pose2 robot{10.0, 5.0, 0.5 * M_PI};
  EXPECT_TRUE(vis.sees(robot, robot.transform({1.0, 0.0}), 0.5));
  EXPECT_FALSE(vis.sees(robot, robot.transform({0.0, 2.0}), 0.5));
  EXPECT_FALSE(vis.sees(robot, robot.transform({0.0, 3.6}), 0.5));
  EXPECT_TRUE(vis.sees(robot, robot.transform({0.0, 3.7}), 0.5));
  // A taller object beside the robot reaches the LiDAR's lowest ring closer: 1.0 m at 1.77 m.
  EXPECT_FALSE(vis.sees(robot, robot.transform({0.0, 1.74}), 1.0));
  EXPECT_TRUE(vis.sees(robot, robot.transform({0.0, 1.80}), 1.0));
  // No sensors: nothing is seen.
  EXPECT_FALSE(SensorVisibility().sees(robot, robot.transform({1.0, 0.0}), 0.5));
  SensorVisibilityParams bad;
  bad.depth_min_range_m = 5.0;
  EXPECT_THROW(SensorVisibility(digit_sensors(), bad), Error);
}

}  // namespace bipednav::tracking
