#include "bipednav/navigation/sensor_gate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"

using namespace bipednav;
using namespace bipednav::navigation;

namespace {

SensorFrame frame(double t, bool lidar, bool depth, float depth_value = 1.0f) {
  SensorFrame f;
  f.stamp_s = t;
  f.odometry = Odometry{t, Pose2{}, Twist{}};
  if (lidar) {
    PointCloud c;
    c.stamp_s = t - 0.1;
    c.points.assign(5, Eigen::Vector3f(1, 1, 1));
    f.lidar = c;
  }
  if (depth) {
    PointCloud c;
    c.stamp_s = t;
    c.points.assign(100, Eigen::Vector3f(depth_value, 0, 0));
    f.depth.push_back({"cam", c});
  }
  return f;
}

TEST(SensorGate, AdmitsFreshDataAndTracksEachSensor) {
  SensorGate gate({}, "lidar", {"cam"});
  const SensorFrame f = gate.admit(frame(0.1, true, true));
  EXPECT_TRUE(f.lidar && f.odometry);
  EXPECT_EQ(f.depth.size(), 1u);
  EXPECT_TRUE(gate.all_alive(0.5));
  gate.admit(frame(0.2, false, true));  // the LiDAR goes quiet, the camera keeps talking
  for (double t = 0.3; t < 0.75; t += 0.1) gate.admit(frame(t, false, true));
  EXPECT_FALSE(gate.all_alive(0.7));
  EXPECT_EQ(gate.silent(0.7), std::vector<std::string>{"lidar"});
  gate.admit(frame(0.8, true, true));
  EXPECT_TRUE(gate.all_alive(0.8));
}

TEST(SensorGate, DropsStaleOutOfOrderAndNonFiniteStamps) {
  SensorGate gate({}, "lidar", {"cam"});
  gate.admit(frame(1.0, true, true));
  SensorFrame stale = frame(1.1, true, true);
  stale.odometry->stamp_s = 0.5;
  stale.lidar->stamp_s = 0.5;
  const SensorFrame s = gate.admit(stale);
  EXPECT_FALSE(s.odometry.has_value());
  EXPECT_FALSE(s.lidar.has_value());
  EXPECT_EQ(s.depth.size(), 1u);
  EXPECT_EQ(gate.counters().stale + gate.counters().out_of_order, 2u);
  SensorFrame back = frame(1.2, false, false);
  back.odometry->stamp_s = 1.0;  // not newer than the last admitted odometry
  EXPECT_FALSE(gate.admit(back).odometry.has_value());
  SensorFrame nan = frame(1.3, false, false);
  nan.odometry->stamp_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(gate.admit(nan).odometry.has_value());
  EXPECT_GE(gate.counters().invalid, 1u);
}

TEST(SensorGate, AFrameFromThePastIsDroppedWhole) {
  SensorGate gate({}, "lidar", {});
  gate.admit(frame(2.0, true, false));
  const SensorFrame f = gate.admit(frame(1.0, true, false));
  EXPECT_FALSE(f.lidar || f.odometry);
  EXPECT_DOUBLE_EQ(f.stamp_s, 2.0);
  EXPECT_EQ(gate.counters().frames_out_of_order, 1u);
}

TEST(SensorGate, ANanDepthCloudIsADropoutOfThatCamera) {
  SensorGate gate({}, "", {"cam"});
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (double t = 0.0; t < 1.0; t += 0.1) EXPECT_TRUE(gate.admit(frame(t, false, true, nan)).depth.empty());
  EXPECT_FALSE(gate.all_alive(0.9));
  EXPECT_EQ(gate.admit(frame(1.0, false, true)).depth.size(), 1u);
  EXPECT_TRUE(gate.all_alive(1.0));
}

TEST(SensorGate, RejectsBadParameters) {
  SensorGateParams p;
  p.max_age_s = 0.0;
  EXPECT_THROW(SensorGate(p, "lidar", {}), ParamError);
}

}  // namespace
