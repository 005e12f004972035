#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/raycaster.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::sim;
using Eigen::Vector3d;

World single(const Geometry& g) {
  World w;
  w.statics.push_back(g);
  return w;
}

TEST(RayCaster, BoxFaceDistanceIsExact) {
  const RayCaster rc(single({"box", make_se3(3, 0, 0.5, 0, 0, 0), Box{{1, 2, 1}}}));
  EXPECT_NEAR(rc.cast({0, 0, 0.5}, {1, 0, 0}, 100.f), 2.5, 1e-5);
  // Oblique ray to the same face: 2.5 / cos(20 deg).
  const double a = 0.35;
  EXPECT_NEAR(rc.cast({0, 0, 0.5}, {std::cos(a), std::sin(a), 0}, 100.f), 2.5 / std::cos(a), 1e-4);
  EXPECT_TRUE(std::isinf(rc.cast({0, 0, 0.5}, {-1, 0, 0}, 100.f)));
  EXPECT_TRUE(std::isinf(rc.cast({0, 0, 0.5}, {1, 0, 0}, 2.0f)));  // beyond max range
}

TEST(RayCaster, CylinderMatchesAnalyticWithin2mm) {
  const double r = 0.15;
  const RayCaster rc(single({"cyl", make_se3(2, 1, 1, 0, 0, 0), Cylinder{r, 2.0}}));
  for (int i = 0; i < 200; ++i) {
    const double off = -0.149 + 0.298 * i / 199.0;  // lateral offsets across the cylinder
    const Vector3d o(0, 1 + off, 0.7);
    const double expected = 2.0 - std::sqrt(r * r - off * off);
    const double range = rc.cast(o, {1, 0, 0}, 50.f);
    // The surface is within 1 mm of the true one; near grazing the range error grows as
    // 1 / cos(incidence), so ranges are compared away from the silhouette.
    EXPECT_NEAR(std::hypot(range - 2.0, off), r, 1e-3) << off;
    if (std::abs(off) < 0.9 * r) {
      EXPECT_NEAR(range, expected, 2e-3) << off;
    }
  }
  // Many directions from a fixed origin.
  for (int i = 0; i < 100; ++i) {
    const double yaw = -0.07 + 0.14 * i / 99.0;
    const Vector3d o(0, 1, 1.2), d(std::cos(yaw), std::sin(yaw), 0);
    const Vector3d c(2, 1, 0);
    const double b = d.head<2>().dot((o - c).head<2>()), cc = (o - c).head<2>().squaredNorm() - r * r;
    const double disc = b * b - cc;
    if (disc < 0.2 * r * r) continue;  // away from the silhouette (see above)
    EXPECT_NEAR(rc.cast(o, d, 50.f), -b - std::sqrt(disc), 2e-3);
  }
}

TEST(RayCaster, SphereAndPlaneMatchAnalytic) {
  World w;
  w.statics.push_back({"sphere", make_se3(0, 0, 2, 0, 0, 0), Sphere{0.5}});
  w.statics.push_back({"ground", SE3::Identity(), Plane{}});
  const RayCaster rc(w);
  for (int i = 0; i < 50; ++i) {
    const double el = -0.4 + 0.8 * i / 49.0;  // rays from below fanning across the sphere
    const Vector3d o(0.0, 0.3 * std::sin(el), 0.0), d(0, 0, 1);
    const double rho2 = o.y() * o.y();
    EXPECT_NEAR(rc.cast(o + Vector3d(0, 0, 0.001), d, 50.f), 2.0 - std::sqrt(0.25 - rho2) - 0.001, 2e-3);
  }
  // Ground plane at z = 0 from a 1.474 m high sensor at -15 deg: 5.5 m horizontal.
  const double el = 15.0 * std::numbers::pi / 180.0;
  const float range = rc.cast({10, 10, 1.474}, {std::cos(el), 0, -std::sin(el)}, 100.f);
  EXPECT_NEAR(range * std::cos(el), 1.474 / std::tan(el), 2e-3);
  // A bounded, tilted plane: 45 deg wall through (5, 0, 0) with normal (-1, 0, 1)/sqrt2.
  const RayCaster tilted(single({"wall", make_se3(5, 0, 0, 0, 0, 0), Plane{{-1, 0, 1}, {4, 4}}}));
  EXPECT_NEAR(tilted.cast({0, 0, 1}, {1, 0, 0}, 50.f), 6.0, 1e-4);
}

TEST(RayCaster, ActorsMoveWithTime) {
  World w;
  Actor a;
  a.name = "mover";
  a.parts.push_back({"box", SE3::Identity(), Box{{0.2, 0.2, 2.0}}});
  a.trajectory = {{0.0, make_se3(2, 0, 1, 0, 0, 0)}, {10.0, make_se3(12, 0, 1, 0, 0, 0)}};
  a.loop = false;
  w.actors.push_back(a);
  w.statics.push_back({"far", make_se3(30, 0, 1, 0, 0, 0), Box{{1, 10, 2}}});
  RayCaster rc(w);
  EXPECT_NEAR(rc.cast({0, 0, 1}, {1, 0, 0}, 100.f), 1.9, 1e-5);
  rc.set_time(5.0);
  EXPECT_NEAR(rc.cast({0, 0, 1}, {1, 0, 0}, 100.f), 6.9, 1e-5);
  rc.set_time(20.0);
  EXPECT_NEAR(rc.cast({0, 0, 1}, {1, 0, 0}, 100.f), 11.9, 1e-5);
  EXPECT_NEAR(rc.cast({0, 1, 1}, {1, 0, 0}, 100.f), 29.5, 1e-4);  // static still there

  // Batch casting agrees with single rays (also for partial packets).
  std::vector<Eigen::Vector3f> dirs;
  for (int i = 0; i < 37; ++i) dirs.push_back(Eigen::Vector3f(1, 0.01f * i - 0.18f, 0).normalized());
  std::vector<float> ranges(dirs.size());
  rc.cast_batch({0, 0, 1}, dirs, 100.f, ranges);
  for (std::size_t i = 0; i < dirs.size(); ++i)
    EXPECT_FLOAT_EQ(ranges[i], rc.cast({0, 0, 1}, dirs[i].cast<double>(), 100.f));
  RayCaster moved = std::move(rc);
  EXPECT_NEAR(moved.cast({0, 0, 1}, {1, 0, 0}, 100.f), 11.9, 1e-5);
}

TEST(RayCaster, RejectsBadInput) {
  EXPECT_THROW(RayCaster(single({"b", SE3::Identity(), Box{{1, -1, 1}}})), ParamError);
  EXPECT_THROW(RayCaster(single({"c", SE3::Identity(), Cylinder{0.0, 1.0}})), ParamError);
  Mesh bad;
  bad.vertices = {{0, 0, 0}, {1, 0, 0}};
  bad.triangles = {{0, 1, 2}};
  EXPECT_THROW(RayCaster(single({"m", SE3::Identity(), bad})), ParamError);
  RayCasterParams p;
  p.threads = 0;
  EXPECT_THROW(RayCaster(World{}, p), ParamError);
  const RayCaster empty{World{}};
  EXPECT_TRUE(std::isinf(empty.cast({0, 0, 0}, {1, 0, 0}, 10.f)));
  EXPECT_THROW(empty.cast({0, 0, 0}, {0, 0, 0}, 10.f), Error);
}

}  // namespace
