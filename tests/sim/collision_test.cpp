#include "bipednav/sim/collision.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/simulation.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::sim;
using Eigen::Vector2d;

TEST(Footprint2D, HullAndSignedDistance) {
  const auto hull = convex_hull({{0, 0}, {2, 0}, {2, 1}, {0, 1}, {1, 0.5}, {1, 0}});
  ASSERT_EQ(hull.size(), 4u);
  Footprint2D f;
  f.polygon = hull;
  EXPECT_NEAR(signed_distance(f, {3, 0.5}), 1.0, 1e-12);
  EXPECT_NEAR(signed_distance(f, {1, 0.4}), -0.4, 1e-12);
  EXPECT_NEAR(signed_distance(f, {3, 2}), std::sqrt(2.0), 1e-12);
  EXPECT_TRUE(closest_point(f, {1, -3}).isApprox(Vector2d(1, 0)));
  const auto clipped = clip_to_slab({{0, 0, -1}, {1, 0, 1}, {0, 1, 1}}, 0.0, 0.5);
  for (const auto& q : clipped) EXPECT_TRUE(q.z() >= -1e-12 && q.z() <= 0.5 + 1e-12);
  EXPECT_EQ(clipped.size(), 4u);
}

TEST(CollisionChecker, ClearanceToEachShapeKind) {
  World w;
  w.statics.push_back({"ground", SE3::Identity(), Plane{}});  // not an obstacle
  w.statics.push_back({"cyl", make_se3(1, 0, 0.5, 0, 0, 0), Cylinder{0.15, 1.0}});
  w.statics.push_back({"box", make_se3(-2, 0, 0.5, 0, 0, M_PI / 4), Box{{1, 1, 1}}});
  w.statics.push_back({"ball", make_se3(0, 3, 2.0, 0, 0, 0), Sphere{0.5}});         // dips to z = 1.5
  w.statics.push_back({"shelf", make_se3(0, -3, 1.9, 0, 0, 0), Box{{1, 1, 0.2}}});  // above the robot
  Mesh tri;
  tri.vertices = {{5, -1, 0}, {5, 1, 0}, {5, 0, 1}};
  tri.triangles = {{0, 1, 2}};
  w.statics.push_back({"mesh", SE3::Identity(), tri});
  const CollisionChecker cc(w, 0.2, 1.6);
  EXPECT_EQ(cc.static_footprint_count(), 4u);  // cyl, box, ball slice, mesh triangle
  Proximity p = cc.nearest({0, 0}, 0.0);
  EXPECT_NEAR(p.clearance_m, 1.0 - 0.15 - 0.2, 1e-9);
  EXPECT_EQ(p.obstacle, "cyl");
  EXPECT_TRUE(p.point.isApprox(Vector2d(0.85, 0), 1e-9));
  // Rotated box: corner at x = -2 + sqrt(0.5).
  EXPECT_NEAR(cc.clearance_m({-0.5, 0}, 0.0), 1.5 - std::sqrt(0.5) - 0.2, 1e-9);
  // Sphere sliced at the robot's top (z = 1.6): radius sqrt(0.25 - 0.16) = 0.3.
  EXPECT_NEAR(cc.clearance_m({0, 2.0}, 0.0), 1.0 - 0.3 - 0.2, 1e-9);
  EXPECT_GT(cc.clearance_m({0, -3}, 0.0), 0.5);                   // under the shelf is free
  EXPECT_NEAR(cc.clearance_m({4.5, 0.0}, 0.0), 0.5 - 0.2, 1e-9);  // mesh triangle footprint x = 5
  EXPECT_NEAR(cc.clearance_m({1.1, 0}, 0.0), -0.25, 1e-9);        // penetration is negative
  EXPECT_TRUE(cc.in_collision({1.1, 0}, 0.0));
  EXPECT_THROW(CollisionChecker(w, -1, 1), ParamError);
  EXPECT_THROW(cc.nearest({NAN, 0}, 0), Error);
}

TEST(CollisionChecker, ActorsAtTheirPoseInTime) {
  World w;
  Actor a;
  a.name = "walker";
  a.parts.push_back({"body", SE3::Identity(), Box{{0.2, 0.2, 2.0}}});
  a.trajectory = {{0, make_se3(5, 0, 1, 0, 0, 0)}, {10, make_se3(-5, 0, 1, 0, 0, 0)}};
  a.loop = false;
  w.actors.push_back(a);
  const CollisionChecker cc(w, 0.3, 1.0);
  EXPECT_NEAR(cc.clearance_m({0, 0}, 0.0), 5 - 0.1 - 0.3, 1e-6);  // float vertices
  const Proximity p = cc.nearest({0, 0}, 5.0);
  EXPECT_LT(p.clearance_m, 0);
  EXPECT_EQ(p.obstacle, "walker/body");
}

TEST(Simulation, DrivingIntoABoxReportsTheFirstCollision) {
  World w;
  w.statics.push_back({"crate", make_se3(3, 0, 0.5, 0, 0, 0), Box{{1, 1, 1}}});  // face at x = 2.5
  RobotProfile tb;                                                               // defaults: radius 0.2, 0.26 m/s
  tb.sensors.clear();
  SimulationParams p;
  p.enable_lidar = p.enable_depth = false;
  Simulation sim(w, tb, Pose2{0, 0, 0}, p);
  EXPECT_NEAR(sim.clearance_m(), 2.5 - 0.2, 1e-9);
  double touch_time = -1;
  while (sim.now_s() < 15.0 && !sim.first_collision()) {
    const double x_before = sim.true_pose().x;
    sim.step(Twist{0.26, 0, 0});
    if (touch_time < 0 && sim.true_pose().x >= 2.3) touch_time = sim.now_s();
    ASSERT_LT(x_before, 2.3 + 1e-9);
  }
  ASSERT_TRUE(sim.first_collision());
  const CollisionEvent& c = *sim.first_collision();
  EXPECT_DOUBLE_EQ(c.time_s, touch_time);  // the first step whose end pose touches the box
  EXPECT_NEAR(c.pose.x, 2.3, 0.26 * 0.01 + 1e-9);
  EXPECT_EQ(c.obstacle, "crate");
  EXPECT_NEAR(c.point.x(), 2.5, 1e-9);
  EXPECT_NEAR(c.point.y(), 0.0, 1e-9);
  EXPECT_GE(c.penetration_m, 0.0);
  EXPECT_LT(sim.min_clearance_m(), 0.0);
  // The robot keeps going (no physics); the first event stays.
  sim.step(Twist{0.26, 0, 0});
  EXPECT_DOUBLE_EQ(sim.first_collision()->time_s, touch_time);
}

}  // namespace
