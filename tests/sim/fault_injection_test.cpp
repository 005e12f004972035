#include "bipednav/sim/fault_injection.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"
#include "bipednav/io/param_reader.hpp"

using namespace bipednav;
using namespace bipednav::sim;

namespace {

Fault fault(FaultType type, double start_s, double duration_s) {
  Fault f;
  f.type = type;
  f.start_s = start_s;
  f.duration_s = duration_s;
  return f;
}

// A frame at t with an odometry pose moving 0.1 m/s along x, a sweep and one depth cloud.
SensorFrame frame_at(double t) {
  SensorFrame f;
  f.stamp_s = t;
  f.odometry = Odometry{t, Pose2{0.1 * t, 0.0, 0.0}, Twist{0.1, 0.0, 0.0}};
  PointCloud sweep;
  sweep.stamp_s = t - 0.1;
  sweep.points.assign(10, Eigen::Vector3f(1, 2, 3));
  f.lidar = sweep;
  PointCloud depth;
  depth.stamp_s = t;
  depth.points.assign(1000, Eigen::Vector3f(1, 0, 0));
  f.depth.push_back({"depth_front", depth});
  return f;
}

TEST(FaultInjection, LidarDropoutRemovesSweepsOnlyDuringTheFault) {
  FaultInjector inj({fault(FaultType::LIDAR_DROPOUT, 1.0, 0.5)}, 1);
  EXPECT_TRUE(inj.apply(frame_at(0.99)).lidar.has_value());
  EXPECT_FALSE(inj.apply(frame_at(1.0)).lidar.has_value());
  EXPECT_FALSE(inj.apply(frame_at(1.49)).lidar.has_value());
  EXPECT_TRUE(inj.apply(frame_at(1.5)).lidar.has_value());
  EXPECT_EQ(inj.counters().sweeps_dropped, 2u);
}

TEST(FaultInjection, DepthNanBurstTurnsTheGivenShareOfPointsIntoNan) {
  Fault all = fault(FaultType::DEPTH_NAN_BURST, 0.0, 1.0);
  FaultInjector inj({all}, 1);
  // Bound first: a range-for over a member of apply()'s temporary read freed memory (ASan).
  const SensorFrame nan_frame = inj.apply(frame_at(0.5));
  for (const auto& p : nan_frame.depth[0].cloud.points) EXPECT_TRUE(std::isnan(p.x()));
  Fault half = all;
  half.nan_fraction = 0.5;
  FaultInjector inj2({half}, 1);
  const auto cloud = inj2.apply(frame_at(0.5)).depth[0].cloud;
  int nan = 0;
  for (const auto& p : cloud.points) nan += std::isnan(p.x()) ? 1 : 0;
  EXPECT_NEAR(nan, 500, 60);
  EXPECT_TRUE(inj2.apply(frame_at(1.5)).depth[0].cloud.points[0].allFinite());
}

TEST(FaultInjection, LocalizationJumpOffsetsTheOdometryOnceAndKeepsItsIncrements) {
  Fault j = fault(FaultType::LOCALIZATION_JUMP, 1.0, 1.0);
  j.jump = {0.5, -0.2, 0.0};
  FaultInjector inj({j}, 1);
  EXPECT_NEAR(inj.apply(frame_at(0.5)).odometry->T_odom_base.x, 0.05, 1e-12);
  const Pose2 a = inj.apply(frame_at(1.0)).odometry->T_odom_base;
  EXPECT_NEAR(a.x, 0.1 + 0.5, 1e-12);
  EXPECT_NEAR(a.y, -0.2, 1e-12);
  const Pose2 b = inj.apply(frame_at(3.0)).odometry->T_odom_base;  // long after: still offset, once
  EXPECT_NEAR(b.x, 0.3 + 0.5, 1e-12);
  EXPECT_EQ(inj.counters().odometry_jumps, 1u);
}

TEST(FaultInjection, OdometrySlipScalesTheReportedMotion) {
  Fault s = fault(FaultType::ODOMETRY_SLIP, 1.0, 1.0);
  s.slip_scale = 0.5;
  FaultInjector inj({s}, 1);
  inj.apply(frame_at(1.0));
  const auto during = inj.apply(frame_at(2.0 - 1e-9)).odometry;  // 0.1 m true -> 0.05 reported
  EXPECT_NEAR(during->T_odom_base.x, 0.1 + 0.05, 1e-6);
  EXPECT_NEAR(during->velocity.linear_x, 0.05, 1e-12);
  const auto after = inj.apply(frame_at(3.0)).odometry;  // increments exact again afterwards
  EXPECT_NEAR(after->T_odom_base.x, 0.15 + 0.1, 1e-6);
}

TEST(FaultInjection, StaleAndOutOfOrderTimestamps) {
  Fault stale = fault(FaultType::STALE_TIMESTAMPS, 0.0, 1.0);
  stale.delay_s = 0.8;
  FaultInjector inj({stale, fault(FaultType::OUT_OF_ORDER_TIMESTAMPS, 2.0, 1.0)}, 1);
  const SensorFrame f = inj.apply(frame_at(0.5));
  EXPECT_DOUBLE_EQ(f.stamp_s, 0.5);  // the frame's clock is untouched
  EXPECT_NEAR(f.odometry->stamp_s, 0.5 - 0.8, 1e-12);
  EXPECT_NEAR(f.lidar->stamp_s, 0.4 - 0.8, 1e-12);
  EXPECT_NEAR(f.depth[0].cloud.stamp_s, 0.5 - 0.8, 1e-12);
  std::vector<double> stamps;
  for (double t = 2.0; t < 2.05; t += 0.01) stamps.push_back(inj.apply(frame_at(t)).odometry->stamp_s);
  int backwards = 0;
  for (std::size_t i = 1; i < stamps.size(); ++i) backwards += stamps[i] < stamps[i - 1] ? 1 : 0;
  EXPECT_GE(backwards, 2);
  EXPECT_GT(inj.counters().messages_reordered, 0u);
}

TEST(FaultInjection, GoalFloodGivesRandomGoalsThenTheGoalInForceAgain) {
  const std::vector<TimedGoal> goals{{0.0, Pose2{5, 0, 0}}, {20.0, Pose2{6, 1, 0}}};
  Fault flood = fault(FaultType::GOAL_FLOOD, 3.0, 2.0);
  flood.goal_count = 10;
  const Bounds b{-1, -2, 7, 2};
  const auto out = goals_with_floods(goals, {flood}, b, 4);
  ASSERT_EQ(out.size(), 2u + 10u + 1u);
  for (std::size_t i = 1; i < out.size(); ++i) EXPECT_LE(out[i - 1].time_s, out[i].time_s);
  for (const auto& g : out) EXPECT_TRUE(b.contains(g.pose.x, g.pose.y));
  EXPECT_DOUBLE_EQ(out[11].time_s, 5.0);  // the flood's end re-gives goal 1
  EXPECT_DOUBLE_EQ(out[11].pose.x, 5.0);
  EXPECT_DOUBLE_EQ(out.back().pose.x, 6.0);
  EXPECT_EQ(goals_with_floods(goals, {flood}, b, 4)[3].pose.x, out[3].pose.x);  // seeded
}

TEST(FaultInjection, CommandDropoutLosesTheCommandsSentWhileItLasts) {
  FaultInjector inj({fault(FaultType::COMMAND_DROPOUT, 2.0, 1.5)}, 1);
  EXPECT_FALSE(inj.has_sensor_faults());  // the frames need not pass through apply()
  EXPECT_TRUE(FaultInjector({fault(FaultType::LIDAR_DROPOUT, 2.0, 1.5)}, 1).has_sensor_faults());
  EXPECT_FALSE(inj.drops_command(1.99));
  EXPECT_TRUE(inj.drops_command(2.0));
  EXPECT_TRUE(inj.drops_command(3.49));
  EXPECT_FALSE(inj.drops_command(3.5));
  EXPECT_EQ(inj.counters().commands_dropped, 2u);
  const SensorFrame f = inj.apply(frame_at(2.5));  // the sensors are untouched
  ASSERT_TRUE(f.lidar.has_value());
  EXPECT_EQ(f.lidar->points.size(), 10u);
  EXPECT_EQ(parse_fault("command_dropout:1:2").type, FaultType::COMMAND_DROPOUT);
  EXPECT_THROW(parse_fault("command_dropout:1:2:3"), Error);  // takes no value
}

TEST(FaultInjection, ParsesSpecsAndRejectsBadOnes) {
  const Fault j = parse_fault("localization_jump:4:1:0.5,0,0.1");
  EXPECT_EQ(j.type, FaultType::LOCALIZATION_JUMP);
  EXPECT_DOUBLE_EQ(j.jump.x, 0.5);
  EXPECT_DOUBLE_EQ(j.jump.theta, 0.1);
  EXPECT_EQ(parse_fault("goal_flood:1:2:7").goal_count, 7);
  EXPECT_DOUBLE_EQ(parse_fault("depth_nan_burst:1:2:0.25").nan_fraction, 0.25);
  EXPECT_THROW(parse_fault("lidar_dropout:1"), Error);
  EXPECT_THROW(parse_fault("meteor:1:2"), Error);
  EXPECT_THROW(parse_fault("lidar_dropout:1:2:3"), Error);
  EXPECT_THROW(parse_fault("lidar_dropout:x:2"), Error);
  EXPECT_THROW(parse_fault("lidar_dropout:1:-2"), Error);
  EXPECT_THROW(parse_fault("depth_nan_burst:1:2:1.5"), Error);
}

TEST(FaultInjection, ReadsScenarioEntriesAndNamesTheBadField) {
  auto r = io::ParamReader::from_string("{type: odometry_slip, start_s: 2, duration_s: 3, slip_scale: 1.5}", "f.yaml");
  const Fault f = read_fault(r);
  EXPECT_EQ(f.type, FaultType::ODOMETRY_SLIP);
  EXPECT_DOUBLE_EQ(f.slip_scale, 1.5);
  auto bad = io::ParamReader::from_string("{type: lidar_dropout, start_s: 2, duration: 3}", "f.yaml");
  try {
    read_fault(bad);
    FAIL() << "an unknown key must be rejected";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("duration"), std::string::npos) << e.what();
  }
  auto unknown = io::ParamReader::from_string("{type: gremlins, start_s: 2}", "f.yaml");
  EXPECT_THROW(read_fault(unknown), Error);
}

}  // namespace
