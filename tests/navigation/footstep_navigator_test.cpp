#include "bipednav/navigation/footstep_navigator.hpp"

#include <gtest/gtest.h>

#include "bipednav/navigation/obstacle_margin.hpp"

namespace bipednav::navigation {
namespace {

mapping::GridGeometry grid() { return {200, 100, 0.01, -0.5, -0.5}; }

FootstepNavigatorParams params() {
  FootstepNavigatorParams p;
  p.gicp_correction = false;
  return p;
}

// Executes every decision perfectly (the landed foot is the target) until the navigator stops.
std::pair<StepDecision, int> walk(FootstepNavigator& nav, planning::footstep::Footstep stance, int max_steps = 200) {
  for (int i = 0; i < max_steps; ++i) {
    const StepDecision d = nav.next(stance);
    if (d.done) return {d, i};
    EXPECT_NE(d.action, nullptr);
    EXPECT_NE(d.target.foot, stance.foot);
    stance = d.target;
  }
  return {StepDecision{}, max_steps};
}

// A horizontal grid of points at height z over [x0, x1] x [y0, y1] (a flat top seen from above).
DepthView slab(double x0, double x1, double y0, double y1, double z) {
  DepthView v;
  v.T_base_sensor = make_se3(0, 0, 1.0, 0, 0, 0);
  for (double x = x0; x <= x1; x += 0.005)
    for (double y = y0; y <= y1; y += 0.005)
      v.cloud_sensor.points.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z - 1.0));
  return v;
}

TEST(FootstepNavigator, WithoutAGoalThereIsNothingToDo) {
  FootstepNavigator nav(params(), grid());
  const StepDecision d = nav.next({{0, 0.05, 0}, 0.0, planning::footstep::Foot::kLeft});
  EXPECT_TRUE(d.done);
  EXPECT_EQ(d.result.outcome, Outcome::INVALID_GOAL);
}

TEST(FootstepNavigator, UnknownGroundIsFreeAndTheGoalIsReached) {
  FootstepNavigator nav(params(), grid());
  nav.set_goal({0.6, 0.0, 0.0});
  const auto [d, steps] = walk(nav, nav.planner().stance_for_body({0, 0, 0}, planning::footstep::Foot::kLeft));
  EXPECT_EQ(d.result.outcome, Outcome::SUCCESS) << d.result.message;
  EXPECT_GE(steps, 6);  // 0.6 m at <= 0.08 m per step and foot
  EXPECT_EQ(nav.plans(), 1u);
}

TEST(FootstepNavigator, AnObservedWallForcesAReplanAroundIt) {
  FootstepNavigator nav(params(), grid());
  nav.set_goal({1.0, 0.0, 0.0});
  planning::footstep::Footstep stance = nav.planner().stance_for_body({0, 0, 0}, planning::footstep::Foot::kLeft);
  StepDecision d = nav.next(stance);
  ASSERT_FALSE(d.done);
  stance = d.target;
  // A 30 cm high, 10 cm deep wall across the straight line, open above y = 0.25.
  nav.observe({slab(0.5, 0.6, -0.5, 0.2, 0.3)}, SE3::Identity());
  d = nav.next(stance);
  EXPECT_TRUE(d.replanned);
  bool above = false;
  for (const auto& f : nav.plan().steps) above |= f.pose.x > 0.45 && f.pose.x < 0.65 && f.pose.y > 0.25;
  EXPECT_TRUE(above);
  const auto [end, steps] = walk(nav, d.target);
  EXPECT_EQ(end.result.outcome, Outcome::SUCCESS) << end.result.message;
}

TEST(FootstepNavigator, AGoalOnAnObstacleIsBlocked) {
  FootstepNavigator nav(params(), grid());
  nav.observe({slab(0.9, 1.1, -0.2, 0.2, 0.3), slab(0.85, 0.9, -0.2, 0.2, 0.0)}, SE3::Identity());
  nav.set_goal({0.9, 0.0, 0.0});  // half on the block, half on the floor: no flat stance
  const StepDecision d = nav.next(nav.planner().stance_for_body({0, 0, 0}, planning::footstep::Foot::kLeft));
  EXPECT_TRUE(d.done);
  EXPECT_EQ(d.result.outcome, Outcome::BLOCKED_GOAL) << d.result.message;
}

TEST(FootstepNavigator, WithoutAPathItTakesBoundedCorrectiveStepsThenGivesUp) {
  // The goal is walled in by 30 cm walls: standable, but unreachable.
  const std::vector<DepthView> ring = {slab(0.7, 0.75, -0.3, 0.3, 0.3), slab(1.25, 1.3, -0.3, 0.3, 0.3),
                                       slab(0.7, 1.3, -0.3, -0.25, 0.3), slab(0.7, 1.3, 0.25, 0.3, 0.3)};
  for (std::size_t max_recovery : {0u, 3u}) {
    FootstepNavigatorParams p = params();
    p.max_recovery_steps = max_recovery;
    FootstepNavigator nav(p, grid());
    nav.observe(ring, SE3::Identity());
    nav.set_goal({1.0, 0.0, 0.0});
    const planning::footstep::Footstep start =
        nav.planner().stance_for_body({0, 0, 0}, planning::footstep::Foot::kLeft);
    planning::footstep::Footstep stance = start;
    int steps = 0;
    StepDecision d;
    for (; steps < 10; ++steps) {
      d = nav.next(stance);
      if (d.done) break;
      ASSERT_NE(d.action, nullptr);
      EXPECT_EQ(d.action->name, "back_4");  // away from what blocks it, one safe planar step
      EXPECT_LT(d.target.pose.x, stance.pose.x);
      stance = d.target;
    }
    EXPECT_EQ(d.result.outcome, Outcome::NO_PATH_FOUND) << d.result.message;
    EXPECT_EQ(steps, static_cast<int>(max_recovery));
    EXPECT_EQ(nav.recoveries(), max_recovery);
  }
}

}  // namespace
}  // namespace bipednav::navigation

namespace bipednav::navigation {
namespace {

TEST(InflateObstacles, WallsGrowBarsDoNot) {
  mapping::Heightmap map({20, 5, 0.01, 0.0, 0.0});
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 20; ++x) map.set(x, y, x == 5 ? 0.05f : (x >= 14 ? 0.5f : 0.0f), 1e-4f);
  map.clear(10, 2);  // unknown cells next to a wall are inflated too
  const mapping::Heightmap out = inflate_obstacles(map, 0.03, 0.08);
  EXPECT_FLOAT_EQ(out.height(4, 2), 0.0f);  // the 5 cm bar is not an obstacle edge
  EXPECT_FLOAT_EQ(out.height(5, 2), 0.05f);
  EXPECT_FALSE(out.known(10, 2));            // 4 cells from the wall: stays unknown
  EXPECT_FLOAT_EQ(out.height(11, 2), 0.5f);  // within 3 cm of the wall's face
  EXPECT_FLOAT_EQ(out.height(10, 1), 0.0f);
  EXPECT_THROW(inflate_obstacles(map, -0.01, 0.08), ParamError);
}

}  // namespace
}  // namespace bipednav::navigation
