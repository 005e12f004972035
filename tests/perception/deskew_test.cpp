// LiDAR motion compensation: points fired along a sweep while the base moves land where the world
// points are at the end of the sweep.
#include "bipednav/perception/deskew.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace bipednav;
using namespace bipednav::perception;

namespace {

// The base pose at time t relative to the base at t0 (t <= t0) for a constant body twist,
// integrated in small steps (the reference for the closed form).
Eigen::Isometry3d base_at(const Twist& v, double dt) {
  const int n = 20000;
  const double h = dt / n;  // negative: integrate backwards
  double x = 0.0, y = 0.0, th = 0.0;
  for (int i = 0; i < n; ++i) {
    const double mid = th + 0.5 * v.angular_z * h;
    x += (v.linear_x * std::cos(mid) - v.linear_y * std::sin(mid)) * h;
    y += (v.linear_x * std::sin(mid) + v.linear_y * std::cos(mid)) * h;
    th += v.angular_z * h;
  }
  return make_se3(x, y, 0.0, 0.0, 0.0, th);
}

// A sweep of fixed world points (given in the base frame at t0 = stamp + 0.1 s), each seen from
// the sensor at its own firing time.
PointCloud sweep_of(const std::vector<Eigen::Vector3d>& world_in_base_t0, const std::vector<float>& offsets,
                    const SE3& T_base_sensor, const Twist& v) {
  PointCloud c;
  c.stamp_s = 10.0;
  for (std::size_t i = 0; i < world_in_base_t0.size(); ++i) {
    const double dt = c.stamp_s + offsets[i] - (c.stamp_s + 0.1);
    const Eigen::Isometry3d T_t0_ti = base_at(v, dt);  // base(ti) in base(t0)
    const Eigen::Vector3d p_sensor = (T_t0_ti * T_base_sensor).inverse() * world_in_base_t0[i];
    c.points.push_back(p_sensor.cast<float>());
    c.time_offsets_s.push_back(offsets[i]);
  }
  return c;
}

}  // namespace

TEST(DeskewSweep, PointsFiredWhileTheBaseTurnsAndDrivesLandWhereTheyAreAtTheSweepsEnd) {
  const SE3 T_base_sensor = make_se3(0.05, -0.02, 1.47, 0.0, 0.0, 0.3);
  const std::vector<Eigen::Vector3d> world = {{2.8, 0.0, 0.2}, {0.0, 3.0, 0.5}, {-2.0, -1.0, 1.0}, {1.0, 1.0, 0.0}};
  const std::vector<float> offsets = {0.0f, 0.025f, 0.05f, 0.1f};
  for (const Twist& v : {Twist{0.0, 0.0, 1.82}, Twist{0.26, 0.0, 0.0}, Twist{0.26, 0.0, -1.5}, Twist{0.3, 0.1, 0.6}}) {
    const PointCloud raw = sweep_of(world, offsets, T_base_sensor, v);
    PointCloud out;
    ASSERT_TRUE(deskew_sweep(raw, T_base_sensor, v, raw.stamp_s + 0.1, out));
    ASSERT_EQ(out.size(), raw.size());
    for (std::size_t i = 0; i < world.size(); ++i) {
      const Eigen::Vector3d in_base = T_base_sensor * out.points[i].cast<double>();
      EXPECT_LT((in_base - world[i]).norm(), 1e-5)
          << "twist " << v.linear_x << "," << v.linear_y << "," << v.angular_z << " point " << i;
    }
    // Without it the first point is off by about the motion over the sweep.
    const Eigen::Vector3d skewed = T_base_sensor * raw.points[0].cast<double>();
    EXPECT_GT((skewed - world[0]).norm(), 0.02);
  }
  // At 1.82 rad/s the start of the sweep is 0.18 rad off: 0.5 m sideways at 2.8 m.
  const PointCloud raw = sweep_of(world, offsets, T_base_sensor, {0.0, 0.0, 1.82});
  EXPECT_NEAR((T_base_sensor * raw.points[0].cast<double>() - world[0]).norm(), 0.51, 0.02);
}

TEST(DeskewSweep, WithoutTimesOrMotionTheSweepIsUsedAsItIs) {
  const SE3 T = make_se3(0.0, 0.0, 1.0, 0.0, 0.0, 0.0);
  PointCloud no_times;
  no_times.points = {{1.0f, 0.0f, 0.0f}};
  PointCloud out;
  out.points = {{7.0f, 7.0f, 7.0f}};
  EXPECT_FALSE(deskew_sweep(no_times, T, {0.2, 0.0, 0.5}, 0.1, out));
  EXPECT_EQ(out.points[0].x(), 7.0f);  // untouched
  PointCloud timed = no_times;
  timed.time_offsets_s = {0.0f};
  EXPECT_FALSE(deskew_sweep(timed, T, {0.0, 0.0, 0.0}, 0.1, out));
  EXPECT_FALSE(deskew_sweep(timed, T, {std::nan(""), 0.0, 0.0}, 0.1, out));
  EXPECT_TRUE(deskew_sweep(timed, T, {0.2, 0.0, 0.0}, 0.1, out));
  // A NaN point stays NaN (the fusion drops it), the rest is moved.
  timed.points.push_back({std::nanf(""), 0.0f, 0.0f});
  timed.time_offsets_s.push_back(0.05f);
  ASSERT_TRUE(deskew_sweep(timed, T, {0.2, 0.0, 0.0}, 0.1, out));
  EXPECT_NEAR(out.points[0].x(), 1.0f - 0.02f, 1e-6);  // fired 0.1 s before: the base was 0.02 m behind
  EXPECT_FALSE(out.points[1].allFinite());
}
