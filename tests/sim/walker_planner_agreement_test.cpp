// The planner's whole-body check (footstep inverse heightmaps) against the walker's collision
// model (sim::upper_body_parts / part_clearance_m) on the same poses: the nao_stairs transition
// where the 16-connected heuristic's plan put the left arm into the side wall (t = 24.5 s of the
// scenario seed, stance and landing from that run).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <optional>

#include "bipednav/planning/footstep/footstep_planner.hpp"
#include "bipednav/sim/humanoid_walker.hpp"

namespace bipednav::sim {
namespace {

// nao_stairs around the platform's left edge at x ~ 1.6: the platform (0.10 m) up to the side
// wall's inner face at y = 0.40, the wall (0.60 m) behind it. `estimated`: what the navigator's
// map held there (the head camera sees only the wall face's lower part: its face cell row read
// 0.10-0.16 m in the run, 0.13 m here; the cells behind are unknown). From 0.14 m on the swing
// foot's band (peak 0.04 m above the stance) already rejects the step.
mapping::Heightmap corridor(bool estimated) {
  const mapping::GridGeometry g{100, 60, 0.01, 1.2, -0.1};
  mapping::Heightmap m(g);
  for (int y = 0; y < g.height; ++y) {
    for (int x = 0; x < g.width; ++x) {
      const double wy = g.cell_center(x, y).y();
      if (wy < 0.40)
        m.set(x, y, 0.10f, 1e-4f);
      else if (!estimated)
        m.set(x, y, 0.60f, 1e-4f);
      else if (wy < 0.41)
        m.set(x, y, 0.13f, 1e-4f);
    }
  }
  return m;
}

planning::footstep::FootstepPlanner planner(double occlusion_rise_m) {
  planning::footstep::FootstepPlannerParams p;
  p.robot = "nao";
  p.occlusion_rise_m = occlusion_rise_m;
  return planning::footstep::FootstepPlanner(p);
}

std::optional<planning::footstep::Footstep> landing(const planning::footstep::FootstepPlanner& pl,
                                                    const mapping::Heightmap& map,
                                                    const planning::footstep::Footstep& from,
                                                    const std::string& action) {
  for (const auto& [name, f] : pl.safe_steps(map, from))
    if (name == action) return f;
  return std::nullopt;
}

// The right stance foot of the run's plan (lattice pose, map frame) before back_turn_out.
const planning::footstep::Footstep kStance{{1.4850, 0.2250, -0.7854}, 0.10, planning::footstep::Foot::kRight};

TEST(WalkerPlannerAgreement, ArmIntoTheWallIsAMapErrorNotACheckDisagreement) {
  const auto est = corridor(true), truth = corridor(false);
  const auto pl = planner(0.0);
  // On the estimated map the planner takes back_turn_out ...
  const auto land = landing(pl, est, kStance, "back_turn_out");
  ASSERT_TRUE(land);
  // ... and the walker's model on the same map agrees: the left arm clears it. On the true map
  // the arm is inside the wall (the run: -0.28 m at (1.607, 0.369)).
  const auto parts = upper_body_parts(pl.lattice().actions().body, kStance.pose, land->pose, kStance.z_m);
  const BodyPart& arm = parts[1];
  std::printf("landing (%.4f, %.4f, %.4f), arm (%.4f, %.4f, %.4f)\n", land->pose.x, land->pose.y, land->pose.theta,
              arm.pose.x, arm.pose.y, arm.pose.theta);
  ASSERT_EQ(arm.name, "left_arm");
  const double c = std::cos(arm.pose.theta), s = std::sin(arm.pose.theta);
  double max_y = -1.0;
  for (double u : {-0.5, 0.5})
    for (double v : {-0.5, 0.5}) {
      const double y = arm.pose.y + s * u * arm.length_m + c * v * arm.width_m;
      std::printf("left arm corner (%.4f, %.4f)\n", arm.pose.x + c * u * arm.length_m - s * v * arm.width_m, y);
      max_y = std::max(max_y, y);
    }
  const double est_clearance = part_clearance_m(est, arm), true_clearance = part_clearance_m(truth, arm);
  std::printf("arm bottom %.3f m, wall face y = 0.40: clearance on the estimated map %.3f m, true %.3f m\n",
              arm.bottom_m, est_clearance, true_clearance);
  EXPECT_GT(max_y, 0.40);                         // the box reaches over the wall's face ...
  EXPECT_NEAR(est_clearance, 0.32 - 0.13, 1e-4);  // ... which the estimated map holds at 0.13 m
  EXPECT_NEAR(true_clearance, 0.32 - 0.60, 1e-4);
  // The two models agree on the same map: on the true map the planner rejects the step too.
  EXPECT_FALSE(landing(pl, truth, kStance, "back_turn_out"));
}

TEST(WalkerPlannerAgreement, OcclusionRiseKeepsTheArmsOffUnknownCellsBehindAFace) {
  const auto est = corridor(true);
  // With the occlusion rule the planner's check on the estimated map is at least as conservative
  // as the walker's on the true one for this transition.
  EXPECT_FALSE(landing(planner(0.02), est, kStance, "back_turn_out"));
  // Without a rising face unknown cells stay free: the same map with the face row at the
  // platform's height (a frontier on flat ground) keeps the step.
  mapping::Heightmap flat = est;
  const auto& g = flat.geometry();
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x)
      if (flat.known(x, y)) flat.set(x, y, 0.10f, 1e-4f);
  EXPECT_TRUE(landing(planner(0.02), flat, kStance, "back_turn_out"));
  // The face's own cell still counts by its height: the planner keeps using the arms' true
  // bottom against the known cells (no extra margin there).
  EXPECT_TRUE(landing(planner(0.0), flat, kStance, "back_turn_out"));
}

}  // namespace
}  // namespace bipednav::sim
