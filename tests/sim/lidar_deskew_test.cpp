// The simulator's VLP-16 fires each column from its own pose; perception::deskew_sweep with the
// base's twist puts a spinning robot's sweep back onto the walls it hit.
#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/io/robot_profile_yaml.hpp"
#include "bipednav/perception/deskew.hpp"
#include "bipednav/sim/simulation.hpp"
#include "test_data.hpp"

using namespace bipednav;
using namespace bipednav::sim;

namespace {

// Mean and largest distance from the east wall's face (x = 3.95) of the sweep's points that hit it,
// each placed with the base's true pose at the frame (the end of the sweep).
std::pair<double, double> east_wall_error(const PointCloud& sweep, const SE3& T_base_sensor, const Pose2& pose) {
  const SE3 T_world_sensor = se3_from_pose2(pose) * T_base_sensor;
  double sum = 0.0, worst = 0.0;
  int n = 0;
  for (const auto& p : sweep.points) {
    const Eigen::Vector3d w = T_world_sensor * p.cast<double>();
    if (w.x() < 3.5 || std::abs(w.y()) > 3.0 || w.z() < 0.2 || w.z() > 2.8) continue;
    const double e = std::abs(w.x() - 3.95);
    sum += e;
    worst = std::max(worst, e);
    ++n;
  }
  EXPECT_GT(n, 50);
  return {n > 0 ? sum / n : 0.0, worst};
}

}  // namespace

TEST(LidarDeskew, ASpinningRobotsSweepLandsOnTheWallOnceDeskewed) {
  World w;
  w.statics.push_back({"e", make_se3(4, 0, 1.5, 0, 0, 0), Box{{0.1, 8, 3}}});
  const RobotProfile tb = io::load_robot_profile(test::source_dir() / "config" / "turtlebot3.yaml");
  SimulationParams p;
  p.seed = 3;
  p.enable_depth = false;
  p.lidar.range_noise_stddev_m = 0.0;
  Simulation sim(w, tb, Pose2{0, 0, 0}, p);
  const SE3 T_base_sensor = tb.lidar()->T_base_sensor();
  int checked = 0;
  for (int i = 0; i < 400 && checked < 3; ++i) {
    const SensorFrame f = sim.step(Twist{0.2, 0.0, 1.82});
    if (!f.lidar || f.stamp_s < 1.5) continue;  // turning at full rate from 0.6 s on
    const auto [skew_mean, skew_worst] = east_wall_error(*f.lidar, T_base_sensor, sim.true_pose());
    PointCloud fixed;
    ASSERT_TRUE(perception::deskew_sweep(*f.lidar, T_base_sensor, sim.true_velocity(), f.stamp_s, fixed));
    const auto [mean, worst] = east_wall_error(fixed, T_base_sensor, sim.true_pose());
    EXPECT_GT(skew_worst, 0.1) << "at " << f.stamp_s;  // the sweep's start is 0.18 rad behind
    EXPECT_LT(worst, 0.01) << "at " << f.stamp_s << " (skewed: mean " << skew_mean << ", worst " << skew_worst << ")";
    EXPECT_LT(mean, 0.003);
    ++checked;
  }
  EXPECT_EQ(checked, 3);
}
