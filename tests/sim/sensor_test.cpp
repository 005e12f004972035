#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/depth_camera.hpp"
#include "bipednav/sim/odometry_model.hpp"
#include "bipednav/sim/vlp16.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::sim;

// A closed 10 x 10 x 6 m room (walls, floor, ceiling) centred on the origin.
World closed_room() {
  World w;
  const double L = 10.0, H = 6.0, t = 0.2;
  w.statics.push_back({"floor", SE3::Identity(), Plane{}});
  w.statics.push_back({"ceiling", make_se3(0, 0, H, 0, 0, 0), Box{{L, L, t}}});
  w.statics.push_back({"n", make_se3(0, L / 2, H / 2, 0, 0, 0), Box{{L, t, H}}});
  w.statics.push_back({"s", make_se3(0, -L / 2, H / 2, 0, 0, 0), Box{{L, t, H}}});
  w.statics.push_back({"e", make_se3(L / 2, 0, H / 2, 0, 0, 0), Box{{t, L, H}}});
  w.statics.push_back({"w", make_se3(-L / 2, 0, H / 2, 0, 0, 0), Box{{t, L, H}}});
  return w;
}

Vlp16Params noiseless_lidar() {
  Vlp16Params p;
  p.range_noise_stddev_m = 0.0;
  return p;
}

TEST(Vlp16, RingElevationsAndFullSweepInClosedRoom) {
  const RayCaster rc(closed_room());
  Vlp16 lidar(noiseless_lidar(), "lidar", 1);
  for (int r = 0; r < 16; ++r) {
    EXPECT_NEAR(rad2deg(lidar.ring_elevation_rad(r)), -15.0 + 2.0 * r, 1e-12);
    EXPECT_NEAR(std::asin(lidar.beam(7, r).z()), lidar.ring_elevation_rad(r), 1e-6);
  }
  EXPECT_NEAR(rad2deg(lidar.column_azimuth_rad(1)), -0.2, 1e-9);  // clockwise, 0.2 deg steps
  const SE3 T = make_se3(0.3, -0.2, 1.0, 0, 0, 0.4);
  EXPECT_FALSE(lidar.fire_until(0.05, rc, [&](double) { return T; }));
  const auto sweep = lidar.fire_until(0.1, rc, [&](double) { return T; });
  ASSERT_TRUE(sweep);
  ASSERT_EQ(sweep->size(), 16u * 1800u);
  ASSERT_TRUE(sweep->is_consistent());
  EXPECT_EQ(sweep->frame_id, "lidar");
  EXPECT_DOUBLE_EQ(sweep->stamp_s, 0.0);
  for (std::size_t i = 0; i < sweep->size(); ++i) {
    const Eigen::Vector3f& p = sweep->points[i];
    const double el = std::atan2(p.z(), std::hypot(p.x(), p.y()));
    ASSERT_NEAR(el, lidar.ring_elevation_rad(sweep->rings[i]), 1e-5);
    ASSERT_EQ(sweep->rings[i], i % 16);
    ASSERT_NEAR(sweep->time_offsets_s[i], (i / 16) * (0.1 / 1800), 1e-7);
  }
  // The next sweep is stamped at its own start.
  const auto second = lidar.fire_until(0.2, rc, [&](double) { return T; });
  ASSERT_TRUE(second);
  EXPECT_NEAR(second->stamp_s, 0.1, 1e-12);
}

TEST(Vlp16, LowestRingMeetsGroundAt5_5m) {
  World w;
  w.statics.push_back({"ground", SE3::Identity(), Plane{}});
  const RayCaster rc(w);
  Vlp16 lidar(noiseless_lidar(), "lidar", 1);
  const double z = 5.5 * std::tan(deg2rad(15.0));
  const auto sweep = lidar.fire_until(0.1, rc, [&](double) { return make_se3(0, 0, z, 0, 0, 0); });
  ASSERT_TRUE(sweep);
  ASSERT_EQ(sweep->size(), 1800u * 8);  // rings 0..7 (-15..-1 deg) hit the ground within 100 m
  for (std::size_t i = 0; i < sweep->size(); ++i)
    if (sweep->rings[i] == 0) {
      ASSERT_NEAR(sweep->points[i].head<2>().norm(), 5.5, 1e-3);
    }
}

TEST(Vlp16, PointsAreInTheSensorFrameAtTheirFiringTime) {
  // The sensor spins at 2 rad/s while it sweeps a closed room: each point, mapped to the world
  // with the pose at its own time, lies on a wall; with the sweep-start pose it does not.
  const RayCaster rc(closed_room());
  Vlp16 lidar(noiseless_lidar(), "lidar", 1);
  const auto pose_at = [](double t) { return make_se3(1.0 + 0.5 * t, 0.5, 1.0, 0, 0, 2.0 * t); };
  const auto sweep = lidar.fire_until(0.1, rc, pose_at);
  ASSERT_TRUE(sweep);
  auto wall_error = [](const Eigen::Vector3d& p) {
    double e = std::abs(p.z());                        // floor
    e = std::min(e, std::abs(p.z() - 5.9));            // ceiling underside
    e = std::min(e, std::abs(std::abs(p.x()) - 4.9));  // inner wall faces
    return std::min(e, std::abs(std::abs(p.y()) - 4.9));
  };
  double max_err = 0.0, max_err_start = 0.0;
  for (std::size_t i = 0; i < sweep->size(); ++i) {
    const Eigen::Vector3d p = sweep->points[i].cast<double>();
    max_err = std::max(max_err, wall_error(pose_at(sweep->time_offsets_s[i]) * p));
    max_err_start = std::max(max_err_start, wall_error(pose_at(0.0) * p));
  }
  EXPECT_LT(max_err, 2e-3);
  EXPECT_GT(max_err_start, 0.5);  // motion distortion is real
}

TEST(DepthCamera, FieldOfViewAndExactDepthOnAWall) {
  World w;
  w.statics.push_back({"wall", make_se3(3.0, 0, 0, 0, 0, 0), Box{{2.0, 100, 100}}});  // face at x = 2
  const RayCaster rc(w);
  DepthCameraParams p;
  p.noise_coeff_per_m = 0.0;
  DepthCamera cam(p, "depth_front", 3);
  const PointCloud c = cam.capture(SE3::Identity(), rc);
  ASSERT_EQ(c.size(), 424u * 240u);
  EXPECT_EQ(c.frame_id, "depth_front");
  double max_h = 0, max_v = 0;
  for (const auto& q : c.points) {
    ASSERT_TRUE(q.allFinite());
    ASSERT_NEAR(q.x(), 2.0, 1e-4);
    max_h = std::max(max_h, std::abs(q.y() / q.x()) + 0.0);
    max_v = std::max(max_v, std::abs(q.z() / q.x()) + 0.0);
  }
  // Outermost pixel centres sit half a pixel inside the 85 x 58 deg field of view.
  EXPECT_NEAR(max_h, std::tan(deg2rad(42.5)) * 423.0 / 424.0, 1e-5);
  EXPECT_NEAR(max_v, std::tan(deg2rad(29.0)) * 239.0 / 240.0, 1e-5);
  // Row-major from the top-left: pixel (0, 0) looks left (+y) and up (+z).
  EXPECT_GT(c.points[0].y(), 0);
  EXPECT_GT(c.points[0].z(), 0);
  EXPECT_LT(c.points.back().y(), 0);
  EXPECT_LT(c.points.back().z(), 0);
  EXPECT_DOUBLE_EQ(cam.next_capture_s(), 1.0 / 15.0);
}

TEST(DepthCamera, NanWhereNothingOrOutOfRange) {
  World w;
  w.statics.push_back({"ground", SE3::Identity(), Plane{}});
  const RayCaster rc(w);
  DepthCameraParams p;
  p.width = 64;
  p.height = 48;
  DepthCamera cam(p, "depth_front", 3);
  // Level camera 1 m up: the upper half sees sky, the lower half ground, far ground beyond 10 m.
  const PointCloud c = cam.capture(make_se3(0, 0, 1.0, 0, 0, 0), rc);
  ASSERT_EQ(c.size(), 64u * 48u);
  for (int v = 0; v < 48; ++v)
    for (int u = 0; u < 64; ++u) {
      const Eigen::Vector3f& q = c.points[v * 64 + u];
      const Eigen::Vector3f ray = cam.pixel_ray(u, v);
      const double depth_to_ground = ray.z() < 0 ? -1.0 / ray.z() * ray.x() : INFINITY;
      if (depth_to_ground <= 9.5 && depth_to_ground >= 0.2) {
        ASSERT_TRUE(q.allFinite()) << u << "," << v;
        ASSERT_NEAR(q.z(), -1.0, 0.4);
      } else if (depth_to_ground > 10.5) {
        ASSERT_TRUE(q.hasNaN()) << u << "," << v;
      }
    }
  EXPECT_TRUE(c.points.front().hasNaN());  // sky
}

TEST(DepthCamera, NoiseGrowsWithTheSquareOfDepth) {
  for (const double d : {2.0, 6.0}) {
    World w;
    w.statics.push_back({"wall", make_se3(d + 1.0, 0, 0, 0, 0, 0), Box{{2.0, 100, 100}}});
    const RayCaster rc(w);
    DepthCameraParams p;
    p.noise_coeff_per_m = 0.004;
    DepthCamera cam(p, "cam", 11);
    const PointCloud c = cam.capture(SE3::Identity(), rc);
    double sum = 0, sum2 = 0;
    for (const auto& q : c.points) sum += q.x(), sum2 += q.x() * q.x();
    const double n = static_cast<double>(c.size()), mean = sum / n;
    const double sigma = std::sqrt(sum2 / n - mean * mean);
    EXPECT_NEAR(mean, d, 0.01 * d * d * 0.004 + 1e-3);
    EXPECT_NEAR(sigma, 0.004 * d * d, 0.05 * 0.004 * d * d) << d;
  }
}

TEST(OdometryModel, ScaleErrorBiasAndRandomWalk) {
  OdometryParams p;
  p.linear_scale_error = 0.05;
  p.angular_scale_error = 0.0;
  p.yaw_bias_radps = 0.0;
  p.linear_random_walk_m_per_sqrt_s = 0.0;
  p.yaw_random_walk_rad_per_sqrt_s = 0.0;
  p.imu_tilt_noise_rad = 0.0;
  OdometryModel straight(p, 1);
  for (int i = 0; i < 1000; ++i) straight.integrate(Twist{0.5, 0, 0}, 0.01);
  EXPECT_NEAR(straight.pose().x, 5.0 * 1.05, 1e-9);
  EXPECT_NEAR(straight.pose().y, 0.0, 1e-12);
  p.linear_scale_error = 0.0;
  p.yaw_bias_radps = 0.01;
  OdometryModel biased(p, 1);
  for (int i = 0; i < 1000; ++i) biased.integrate(Twist{0, 0, 0}, 0.01);
  EXPECT_NEAR(biased.pose().theta, 0.1, 1e-9);
  const Odometry o = biased.measure(10.0, 0.02, -0.01);
  EXPECT_DOUBLE_EQ(o.roll_rad, 0.02);
  EXPECT_DOUBLE_EQ(o.pitch_rad, -0.01);
  // Random walk: position spread over seeds ~ q sqrt(t).
  p.yaw_bias_radps = 0.0;
  p.linear_random_walk_m_per_sqrt_s = 0.01;
  double sum2 = 0;
  const int runs = 200;
  for (int s = 0; s < runs; ++s) {
    OdometryModel m(p, 100 + s);
    for (int i = 0; i < 400; ++i) m.integrate(Twist{0, 0, 0}, 0.01);
    sum2 += m.pose().x * m.pose().x;
  }
  EXPECT_NEAR(std::sqrt(sum2 / runs), 0.01 * 2.0, 0.004);
}

TEST(Sensors, InvalidParametersNameTheField) {
  Vlp16Params l;
  l.columns = 0;
  try {
    l.validate();
    FAIL();
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("columns"), std::string::npos);
  }
  l = {};
  l.max_range_m = 0.1;
  EXPECT_THROW(Vlp16(l, "lidar", 0), ParamError);
  DepthCameraParams d;
  d.hfov_rad = 4.0;
  EXPECT_THROW(d.validate(), ParamError);
  d = {};
  d.rate_hz = 0;
  EXPECT_THROW(DepthCamera(d, "c", 0), ParamError);
  OdometryParams o;
  o.linear_random_walk_m_per_sqrt_s = -1;
  EXPECT_THROW(OdometryModel(o, 0), ParamError);
}

}  // namespace
