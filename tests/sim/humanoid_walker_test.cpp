#include "bipednav/sim/humanoid_walker.hpp"

#include <gtest/gtest.h>

#include "bipednav/sim/raycaster.hpp"
#include "bipednav/sim/terrain_truth.hpp"

namespace bipednav::sim {
namespace {

mapping::GridGeometry grid() { return {400, 200, 0.005, -0.5, -0.5}; }

// Ground plus one box standing on it (x, y centre; size).
mapping::Heightmap terrain_with_box(double cx, double cy, double sx, double sy, double sz) {
  World w;
  w.statics.push_back({"ground", SE3::Identity(), Plane{}});
  if (sz > 0) w.statics.push_back({"box", make_se3(cx, cy, sz / 2, 0, 0, 0), Box{{sx, sy, sz}}});
  return true_heightmap(RayCaster(w), grid(), 2.0);
}

HumanoidWalkerParams noiseless() {
  HumanoidWalkerParams p;
  p.landing_noise_xy_m = p.landing_noise_yaw_rad = 0.0;
  p.odometry_noise_xy_m = p.odometry_noise_yaw_rad = 0.0;
  return p;
}

TEST(TrueHeightmap, BoxHeightsAndGround) {
  const auto map = terrain_with_box(0.5, 0.0, 0.2, 0.2, 0.1);
  const auto& g = map.geometry();
  const auto on_box = g.world_to_cell(0.5, 0.0), ground = g.world_to_cell(0.0, 0.3);
  EXPECT_NEAR(map.height(on_box->x, on_box->y), 0.1, 1e-4);
  EXPECT_NEAR(map.height(ground->x, ground->y), 0.0, 1e-4);
}

TEST(HumanoidWalker, NoiselessStepLandsExactlyAndOdometryFollows) {
  const auto flat = terrain_with_box(0, 0, 0, 0, 0);
  HumanoidWalker w(noiseless(), flat, {0.0, 0.0, 0.0}, 1);
  EXPECT_EQ(w.stance().foot, Foot::kLeft);
  EXPECT_NEAR(w.stance().pose.y, 0.05, 1e-12);
  const StepExecution e = w.step({{0.08, -0.10, 0.0}, 0.5, 0.04, "fwd_8"});
  EXPECT_TRUE(e.contacts.empty());
  EXPECT_NEAR(e.landed.pose.x, 0.08, 1e-12);
  EXPECT_NEAR(e.landed.pose.y, -0.05, 1e-12);
  EXPECT_EQ(w.stance().foot, Foot::kRight);
  EXPECT_NEAR(w.body_pose().x, 0.04, 1e-12);
  EXPECT_NEAR(w.odom_stance().pose.x, 0.08, 1e-12);
  EXPECT_DOUBLE_EQ(w.time_s(), 0.5);
  EXPECT_NEAR(e.min_clearance_m, 0.04, 1e-9);  // the swing sole 4 cm over flat ground
}

TEST(HumanoidWalker, LandingOnAPlatformTakesItsHeight) {
  const auto map = terrain_with_box(0.3, 0.0, 0.3, 0.6, 0.05);
  HumanoidWalker w(noiseless(), map, {0.0, 0.0, 0.0}, 1);
  const StepExecution e = w.step({{0.24, -0.10, 0.0}, 5.0, 0.10, "step_onto"});
  EXPECT_NEAR(e.landed.z_m, 0.05, 1e-4);
  EXPECT_TRUE(e.contacts.empty());
  EXPECT_NEAR(w.odom_stance().z_m, 0.05, 1e-4);
}

TEST(HumanoidWalker, SwingFootThroughABarIsACollision) {
  // A 5 cm bar just ahead: a planar step (4 cm clearance) hits it, a step-over (8 cm) does not.
  const auto map = terrain_with_box(0.11, 0.0, 0.04, 1.0, 0.05);
  HumanoidWalker low(noiseless(), map, {0.0, 0.0, 0.0}, 1);
  const StepExecution hit = low.step({{0.22, -0.10, 0.0}, 0.5, 0.04, "fwd"});
  ASSERT_EQ(hit.contacts.size(), 1u);
  EXPECT_EQ(hit.contacts[0].part, "swing_foot");
  EXPECT_NEAR(hit.contacts[0].penetration_m, 0.01, 1e-4);
  HumanoidWalker high(noiseless(), map, {0.0, 0.0, 0.0}, 1);
  EXPECT_TRUE(high.step({{0.22, -0.10, 0.0}, 5.5, 0.08, "step_over"}).contacts.empty());
}

TEST(HumanoidWalker, ArmsHitANarrowGapFacingForwards) {
  // Two walls 0.24 m apart along x: the arms (0.29 m) touch them, sideways the body fits.
  World w;
  w.statics.push_back({"ground", SE3::Identity(), Plane{}});
  w.statics.push_back({"wall_l", make_se3(0.5, 0.32, 0.4, 0, 0, 0), Box{{1.0, 0.4, 0.8}}});
  w.statics.push_back({"wall_r", make_se3(0.5, -0.32, 0.4, 0, 0, 0), Box{{1.0, 0.4, 0.8}}});
  const auto map = true_heightmap(RayCaster(w), grid(), 2.0);
  HumanoidWalker fwd(noiseless(), map, {0.3, 0.0, 0.0}, 1);
  const auto e = fwd.step({{0.04, -0.10, 0.0}, 0.5, 0.04, "fwd_4"});
  EXPECT_FALSE(e.contacts.empty());
  HumanoidWalker side(noiseless(), map, {0.3, 0.0, 1.5707963}, 1);
  EXPECT_TRUE(side.step({{0.0, -0.16, 0.0}, 0.5, 0.04, "side_out"}).contacts.empty());
}

TEST(HumanoidWalker, SoleHalfOnAnEdgeFallsButASmallOverhangStands) {
  // A 10 cm platform starting at x = 0.30: a sole centred at x = 0.30 rests half on it (a fall);
  // centred at x = 0.375 only its heel overhangs by 0.5 cm, within the rim tolerance.
  const auto map = terrain_with_box(0.65, 0.0, 0.7, 1.0, 0.1);
  HumanoidWalker half(noiseless(), map, {0.0, 0.0, 0.0}, 1);
  const StepExecution fall = half.step({{0.30, -0.10, 0.0}, 5.0, 0.12, "step_onto"});
  ASSERT_FALSE(fall.contacts.empty());
  EXPECT_EQ(fall.contacts.back().part, "landing_foot");
  EXPECT_NEAR(fall.support_ratio, 0.5, 0.1);
  HumanoidWalker edge(noiseless(), map, {0.2, 0.0, 0.0}, 1);
  const StepExecution ok = edge.step({{0.175, -0.10, 0.0}, 5.0, 0.12, "step_onto"});
  EXPECT_TRUE(ok.contacts.empty());
  EXPECT_NEAR(ok.landed.z_m, 0.1, 1e-4);
}

TEST(HumanoidWalker, RejectsBadInput) {
  const auto flat = terrain_with_box(0, 0, 0, 0, 0);
  HumanoidWalkerParams p;
  p.samples_per_segment = 0;
  EXPECT_THROW(HumanoidWalker(p, flat, {}, 1), ParamError);
  HumanoidWalker w(noiseless(), flat, {}, 1);
  EXPECT_THROW(w.step({{0.0, -0.1, 0.0}, 0.0, 0.04, "x"}), ParamError);
  EXPECT_THROW(w.step({{NAN, -0.1, 0.0}, 0.5, 0.04, "x"}), Error);
}

}  // namespace
}  // namespace bipednav::sim
