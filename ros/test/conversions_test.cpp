#include "ros/conversions.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::ros1 {
namespace {

PointCloud lidar_cloud() {
  PointCloud c;
  c.frame_id = "lidar";
  c.stamp_s = 12.5;
  for (int i = 0; i < 5; ++i) {
    c.points.emplace_back(0.5f * i, -1.0f + i, 0.25f * i);
    c.time_offsets_s.push_back(0.02f * i);
    c.rings.push_back(static_cast<std::uint16_t>(i * 3));
    c.intensities.push_back(10.0f * i);
  }
  return c;
}

TEST(RosConversions, PointCloudRoundTripKeepsEveryField) {
  const PointCloud in = lidar_cloud();
  const auto msg = to_msg(in);
  ASSERT_EQ(msg.fields.size(), 6u);
  EXPECT_EQ(msg.fields[3].name, "intensity");
  EXPECT_EQ(msg.fields[4].name, "time");
  EXPECT_EQ(msg.fields[5].name, "ring");
  EXPECT_EQ(msg.fields[5].datatype, sensor_msgs::PointField::UINT16);
  EXPECT_EQ(msg.point_step, 22u);
  EXPECT_EQ(msg.width, 5u);
  const PointCloud out = from_msg(msg);
  EXPECT_EQ(out.frame_id, "lidar");
  EXPECT_DOUBLE_EQ(out.stamp_s, 12.5);
  ASSERT_EQ(out.size(), in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    EXPECT_EQ(out.points[i], in.points[i]);
    EXPECT_EQ(out.time_offsets_s[i], in.time_offsets_s[i]);
    EXPECT_EQ(out.rings[i], in.rings[i]);
    EXPECT_EQ(out.intensities[i], in.intensities[i]);
  }
}

TEST(RosConversions, PointCloudWithoutOptionalFieldsAndNaNsDropped) {
  PointCloud in;
  in.frame_id = "depth_front";
  in.points = {{1, 2, 3}, {NAN, 0, 0}, {4, 5, 6}};
  const auto msg = to_msg(in);
  EXPECT_EQ(msg.fields.size(), 3u);
  EXPECT_EQ(msg.point_step, 12u);
  const PointCloud out = from_msg(msg);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out.points[1], Eigen::Vector3f(4, 5, 6));
  EXPECT_FALSE(out.has_time());
  EXPECT_FALSE(out.has_ring());
}

TEST(RosConversions, MalformedPointCloudThrows) {
  auto msg = to_msg(lidar_cloud());
  auto short_data = msg;
  short_data.data.resize(10);
  EXPECT_THROW(from_msg(short_data), Error);
  auto no_z = msg;
  no_z.fields.erase(no_z.fields.begin() + 2);
  EXPECT_THROW(from_msg(no_z), Error);
  auto bad_offset = msg;
  bad_offset.fields[5].offset = 100;
  EXPECT_THROW(from_msg(bad_offset), Error);
  PointCloud inconsistent = lidar_cloud();
  inconsistent.rings.pop_back();
  EXPECT_THROW(to_msg(inconsistent), Error);
}

TEST(RosConversions, CostmapToOccupancyGrid) {
  EXPECT_EQ(occupancy_of(0), 0);
  EXPECT_EQ(occupancy_of(1), 1);
  EXPECT_EQ(occupancy_of(253), 99);
  EXPECT_EQ(occupancy_of(254), 100);
  EXPECT_EQ(occupancy_of(255), -1);
  for (int c = 1; c < 253; ++c) EXPECT_LE(occupancy_of(c), occupancy_of(c + 1));
  mapping::GridGeometry g{4, 3, 0.05, -1.0, 2.0};
  mapping::Costmap2D map(g, 0);
  map.set_cost(1, 0, mapping::kLethal);
  map.set_cost(3, 2, mapping::kUnknown);
  const auto msg = to_msg(map, "map", 3.0);
  EXPECT_EQ(msg.info.width, 4u);
  EXPECT_EQ(msg.info.height, 3u);
  EXPECT_FLOAT_EQ(msg.info.resolution, 0.05f);
  EXPECT_DOUBLE_EQ(msg.info.origin.position.x, -1.0);
  EXPECT_DOUBLE_EQ(msg.info.origin.position.y, 2.0);
  EXPECT_EQ(msg.data[1], 100);
  EXPECT_EQ(msg.data[2 * 4 + 3], -1);
  const auto back = from_msg(msg);
  EXPECT_EQ(back.width(), 4);
  EXPECT_EQ(back.cost(1, 0), mapping::kLethal);
  EXPECT_EQ(back.cost(3, 2), mapping::kUnknown);
  EXPECT_EQ(back.cost(0, 0), mapping::kFree);
  auto bad = msg;
  bad.data.pop_back();
  EXPECT_THROW(from_msg(bad), Error);
}

TEST(RosConversions, PathRoundTripWithTimes) {
  Path p;
  p.frame_id = "map";
  p.poses = {{0, 0, 0}, {1, 0.5, 0.3}, {2, 1, -2.5}};
  p.times_s = {0.0, 0.5, 1.0};
  const auto msg = to_msg(p, 100.0);
  ASSERT_EQ(msg.poses.size(), 3u);
  EXPECT_EQ(msg.header.frame_id, "map");
  const Path out = from_msg(msg);
  ASSERT_EQ(out.size(), 3u);
  ASSERT_EQ(out.times_s.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(out.poses[i].x, p.poses[i].x, 1e-12);
    EXPECT_NEAR(out.poses[i].y, p.poses[i].y, 1e-12);
    EXPECT_NEAR(out.poses[i].theta, p.poses[i].theta, 1e-9);
    EXPECT_NEAR(out.times_s[i], p.times_s[i], 1e-6);
  }
  p.times_s.clear();
  EXPECT_TRUE(from_msg(to_msg(p, 5.0)).times_s.empty());
}

TEST(RosConversions, TwistPoseTransformRoundTrips) {
  const Twist t{0.2, -0.1, 0.7};
  const Twist tb = from_msg(to_msg(t));
  EXPECT_EQ(tb.linear_x, 0.2);
  EXPECT_EQ(tb.linear_y, -0.1);
  EXPECT_EQ(tb.angular_z, 0.7);
  for (double yaw : {0.0, 1.0, -3.0, 3.1}) {
    const Pose2 p{1.5, -2.0, yaw};
    const Pose2 q = from_msg(to_pose_msg(p));
    EXPECT_DOUBLE_EQ(q.x, 1.5);
    EXPECT_NEAR(q.theta, yaw, 1e-12);
  }
  const auto tf = to_transform(Pose2{1, 2, M_PI / 2}, "map", "odom", 4.0);
  EXPECT_EQ(tf.header.frame_id, "map");
  EXPECT_EQ(tf.child_frame_id, "odom");
  EXPECT_NEAR(tf.transform.rotation.z, std::sqrt(0.5), 1e-12);
  geometry_msgs::Pose bad;
  bad.position.x = NAN;
  EXPECT_THROW(from_msg(bad), Error);
}

TEST(RosConversions, OdometryRoundTrip) {
  Odometry o;
  o.stamp_s = 7.25;
  o.T_odom_base = {3.0, -1.0, 0.4};
  o.velocity = {0.3, 0.0, -0.2};
  o.roll_rad = 0.01;
  o.pitch_rad = -0.02;
  const auto msg = to_msg(o, "odom", "base_link");
  EXPECT_EQ(msg.child_frame_id, "base_link");
  const Odometry back = from_msg(msg);
  EXPECT_DOUBLE_EQ(back.stamp_s, 7.25);
  EXPECT_DOUBLE_EQ(back.T_odom_base.x, 3.0);
  EXPECT_NEAR(back.T_odom_base.theta, 0.4, 1e-9);
  EXPECT_NEAR(back.roll_rad, 0.01, 1e-9);
  EXPECT_NEAR(back.pitch_rad, -0.02, 1e-9);
  EXPECT_DOUBLE_EQ(back.velocity.angular_z, -0.2);
}

TEST(RosConversions, MarkersShowObstaclesAndFootsteps) {
  mapping::Costmap2D local(mapping::GridGeometry{10, 10, 0.1, 0.0, 0.0}, 0);
  local.set_cost(2, 3, mapping::kLethal);
  local.set_cost(5, 5, mapping::kLethal);
  Path traj;
  for (int i = 0; i <= 10; ++i) traj.poses.push_back({0.1 * i, 0.0, 0.0});
  MarkerInput in;
  in.goal = Pose2{1, 1, 0};
  in.local_costmap = &local;
  in.local_trajectory = &traj;
  in.step_length_m = 0.25;
  const auto arr = to_markers(in);
  ASSERT_EQ(arr.markers.size(), 4u);
  EXPECT_EQ(arr.markers[2].ns, "obstacles");
  ASSERT_EQ(arr.markers[2].points.size(), 2u);
  EXPECT_NEAR(arr.markers[2].points[0].x, 0.25, 1e-9);
  EXPECT_NEAR(arr.markers[2].points[0].y, 0.35, 1e-9);
  EXPECT_EQ(arr.markers[3].ns, "footsteps");
  ASSERT_EQ(arr.markers[3].points.size(), 4u);  // at 0, 0.3, 0.6, 0.9 m
  EXPECT_NEAR(arr.markers[3].points[0].y, 0.1, 1e-9);
  EXPECT_NEAR(arr.markers[3].points[1].y, -0.1, 1e-9);
}

}  // namespace
}  // namespace bipednav::ros1
