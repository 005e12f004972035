#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bipednav/common/error.hpp"
#include "bipednav/io/robot_profile_yaml.hpp"
#include "bipednav/sim/robot_model.hpp"
#include "test_data.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::sim;

RobotProfile load(const std::string& name) {
  return io::load_robot_profile(test::source_dir() / "config" / (name + ".yaml"));
}

TEST(RobotModel, DiffDriveClampsTracksAndLimitsAcceleration) {
  const RobotProfile p = load("turtlebot3");
  RobotModel m(p, Pose2{1, 2, 0});
  const RobotState& s1 = m.step(Twist{5.0, 3.0, 0.0}, 0.01);
  EXPECT_LE(s1.velocity.linear_x, p.limits.acc_lim_x_mps2 * 0.01 + 1e-12);  // acceleration limit
  EXPECT_EQ(s1.velocity.linear_y, 0.0);                                     // lateral ignored
  for (int i = 0; i < 300; ++i) m.step(Twist{5.0, 3.0, 0.0}, 0.01);
  EXPECT_NEAR(m.state().velocity.linear_x, p.limits.max_vel_x_mps, 1e-9);  // clamped
  EXPECT_NEAR(m.state().pose.y, 2.0, 1e-12);                               // no lateral motion
  // First-order lag without saturation: v(t) = target (1 - exp(-t / tau)).
  RobotModel lag(p);
  for (int i = 0; i < 5; ++i) lag.step(Twist{0.01, 0, 0}, 0.01);
  EXPECT_NEAR(lag.state().velocity.linear_x, 0.01 * (1 - std::exp(-0.05 / p.tracking_time_constant_s)), 1e-12);
}

TEST(RobotModel, ExactArcsAndIntraStepPoses) {
  RobotProfile p = load("turtlebot3");
  p.tracking_time_constant_s = 0.0;
  p.limits.acc_lim_x_mps2 = 100;
  p.limits.acc_lim_theta_radps2 = 100;
  RobotModel m(p);
  // v = 0.2, w = 0.5: a circle of radius 0.4 around (0, 0.4); a quarter turn takes pi s.
  for (int i = 0; i < 100; ++i) m.step(Twist{0.2, 0, 0.5}, std::numbers::pi / 100);
  EXPECT_NEAR(m.state().pose.x, 0.4, 1e-9);
  EXPECT_NEAR(m.state().pose.y, 0.4, 1e-9);
  EXPECT_NEAR(m.state().pose.theta, std::numbers::pi / 2, 1e-9);
  const Pose2 end = m.pose_in_last_step(std::numbers::pi / 100);
  EXPECT_NEAR(end.x, m.state().pose.x, 1e-12);
  const Pose2 mid = m.pose_in_last_step(0.5 * std::numbers::pi / 100);
  EXPECT_NEAR(std::hypot(mid.x, mid.y - 0.4), 0.4, 1e-12);  // still on the circle
}

TEST(RobotModel, WalkerLimitsAndSway) {
  const RobotProfile p = load("digit");
  EXPECT_EQ(p.kind, "walker");
  RobotModel m(p);
  for (int i = 0; i < 1000; ++i) m.step(Twist{-1.0, 0.0, 2.0}, 0.01);
  EXPECT_NEAR(m.state().velocity.linear_x, -p.limits.max_vel_x_backwards_mps, 1e-6);
  EXPECT_NEAR(m.state().velocity.angular_z, p.limits.max_vel_theta_radps, 1e-6);
  // Standing: the base sways sideways with the gait, one cycle per two steps.
  RobotModel still(p);
  double max_y = 0, min_y = 0;
  for (int i = 0; i < 200; ++i) {
    still.step(Twist{}, 0.01);
    max_y = std::max(max_y, still.state().pose.y);
    min_y = std::min(min_y, still.state().pose.y);
  }
  EXPECT_NEAR(max_y, p.sway_amplitude_m, 1e-3);
  EXPECT_NEAR(min_y, -p.sway_amplitude_m, 1e-3);
  EXPECT_NEAR(still.state().pose.x, 0.0, 1e-12);
  // At t = 1 s (two steps at 2 Hz) the sway is back at zero, moving left.
  EXPECT_NEAR(still.state().pose.y, std::sin(std::numbers::pi * 2.0 * 2.0) * p.sway_amplitude_m, 1e-9);
  EXPECT_THROW(m.step(Twist{NAN, 0, 0}, 0.01), Error);
  EXPECT_THROW(m.step(Twist{}, 0.0), Error);
}

TEST(RobotProfileYaml, ShippedProfilesMatchTheThesisMounts) {
  const RobotProfile digit = load("digit");
  const SensorMount* lidar = digit.sensor("lidar");
  ASSERT_NE(lidar, nullptr);
  EXPECT_NEAR(lidar->z_m / std::tan(deg2rad(15.0)), 5.5, 0.01);  // first ground return at 5.5 m
  const SensorMount* front = digit.sensor("depth_front");
  const SensorMount* back = digit.sensor("depth_back");
  ASSERT_TRUE(front && back);
  // Optical axes: 45 deg down to the front, 135 deg (45 deg down, facing back).
  const Eigen::Vector3d ax_f = front->T_base_sensor().linear() * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d ax_b = back->T_base_sensor().linear() * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(ax_f.x(), std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(ax_f.z(), -std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(ax_b.x(), -std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(ax_b.z(), -std::sqrt(0.5), 1e-9);
  const RobotProfile tb = load("turtlebot3");
  EXPECT_EQ(tb.kind, "diff_drive");
  EXPECT_EQ(tb.sensors.size(), 3u);
  const RobotProfile nao = load("nao");
  EXPECT_EQ(nao.kind, "humanoid");
  ASSERT_NE(nao.sensor("depth_head"), nullptr);
  EXPECT_NEAR(nao.height_m, 0.58, 0.01);
}

void expect_file_error(const std::string& yaml, const std::vector<std::string>& parts) {
  try {
    io::parse_robot_profile(yaml, "robot.yaml");
    FAIL() << "accepted: " << yaml;
  } catch (const FileError& e) {
    for (const auto& part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
  }
}

TEST(RobotProfileYaml, BadInputNamesFileAndField) {
  expect_file_error("name: x\nmax_vel_x_mps: fast\n", {"robot.yaml", "line 2", "max_vel_x_mps", "number"});
  expect_file_error("name: x\nmax_speed: 1.0\n", {"robot.yaml", "max_speed", "unknown"});
  expect_file_error("sensors:\n  - {name: lidar, type: vlp16, z: 1.4}\n", {"sensors[0].z", "unknown"});
  expect_file_error("sensors:\n  - {type: vlp16}\n", {"sensors[0].name"});
  expect_file_error("sensors:\n  - {name: l, type: vlp16, z_m: high}\n", {"sensors[0].z_m", "number"});
  expect_file_error("footprint_radius_m: -1\n", {"robot.yaml", "footprint_radius_m"});
  expect_file_error("kind: hovercraft\n", {"kind"});
  expect_file_error("sensors: {name: l}\n", {"sensors", "list"});
  EXPECT_THROW(io::load_robot_profile("/nonexistent/robot.yaml"), FileError);
}

}  // namespace
