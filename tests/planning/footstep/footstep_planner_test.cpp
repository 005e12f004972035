#include "bipednav/planning/footstep/footstep_planner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "bipednav/planning/footstep/heuristics.hpp"

using namespace bipednav;
using namespace bipednav::planning::footstep;

namespace {

mapping::Heightmap flat_map(double size_x, double size_y, double res) {
  mapping::GridGeometry g{static_cast<int>(std::lround(size_x / res)), static_cast<int>(std::lround(size_y / res)), res,
                          0.0, 0.0};
  mapping::Heightmap m(g);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) m.set(x, y, 0.0f, 1e-4f);
  return m;
}

void add_box(mapping::Heightmap& m, double x0, double y0, double x1, double y1, double h) {
  const auto& g = m.geometry();
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const auto c = g.cell_center(x, y);
      if (c.x() >= x0 && c.x() < x1 && c.y() >= y0 && c.y() < y1) m.set(x, y, static_cast<float>(h), 1e-4f);
    }
}

// Searches without a wall-clock limit (tests must not depend on machine speed), stopping at
// the first solution with a proven bound of `eps`.
FootstepPlannerParams params_with_bound(double eps) {
  FootstepPlannerParams p;
  p.search.time_limit_s = 0.0;
  p.search.initial_epsilon = std::max(eps, 3.0);
  p.search.target_epsilon = eps;
  return p;
}
FootstepPlannerParams fast_params() { return params_with_bound(3.0); }

bool uses(const FootstepPlan& plan, const std::string& action) {
  return std::find(plan.actions.begin(), plan.actions.end(), action) != plan.actions.end();
}

}  // namespace

TEST(FootstepPlanner, FlatGroundUsesPlanarStepsAndReachesGoal) {
  const auto map = flat_map(1.6, 0.8, 0.01);
  FootstepPlanner planner(params_with_bound(1.0));
  const Footstep start = planner.stance_for_body({0.3, 0.4, 0.0}, Foot::kLeft);
  const FootstepPlan plan = planner.plan(map, start, {1.2, 0.4, 0.0});
  ASSERT_TRUE(plan.result.ok()) << plan.result.message;
  EXPECT_DOUBLE_EQ(plan.final_epsilon, 1.0);
  for (const auto& a : plan.actions) EXPECT_TRUE(a != "step_over" && a != "step_onto" && a != "step_down") << a;
  // Optimal: the body must cover 0.9 m less the 5 cm tolerance, and no 0.5 s step moves it
  // further than the fastest action does, so the bound below is met exactly.
  const ActionSet nao = nao_action_set();
  const double max_step_m = nao.fastest_speed_mps() * 0.5;
  EXPECT_DOUBLE_EQ(plan.cost_s, std::ceil(0.85 / max_step_m) * 0.5);
  const Footstep& last = plan.steps.back();
  const double half = 0.05 * (last.foot == Foot::kLeft ? -1 : 1);
  const Pose2 body = last.pose * Pose2{0, half, 0};
  EXPECT_NEAR(body.x, 1.2, 0.05 + 1e-9);
  EXPECT_NEAR(body.y, 0.4, 0.05 + 1e-9);
  // Feet alternate.
  for (std::size_t i = 1; i < plan.steps.size(); ++i) EXPECT_NE(plan.steps[i].foot, plan.steps[i - 1].foot);
}

TEST(FootstepPlanner, StepsOverABarThatPlanarStepsCannotCross) {
  auto map = flat_map(1.0, 0.5, 0.01);
  add_box(map, 0.48, 0.0, 0.52, 0.5, 0.05);  // a 5 cm bar across the whole map
  FootstepPlanner planner(fast_params());
  const Footstep start = planner.stance_for_body({0.2, 0.25, 0.0}, Foot::kLeft);
  const FootstepPlan plan = planner.plan(map, start, {0.8, 0.25, 0.0});
  ASSERT_TRUE(plan.result.ok()) << plan.result.message;
  EXPECT_TRUE(uses(plan, "step_over"));
  for (const auto& s : plan.steps) EXPECT_NEAR(s.z_m, 0.0, 1e-6);

  FootstepPlannerParams p2 = fast_params();
  p2.planar_only = true;
  FootstepPlanner planar(p2);
  const FootstepPlan blocked = planar.plan(map, start, {0.8, 0.25, 0.0});
  EXPECT_EQ(blocked.result.outcome, Outcome::NO_PATH_FOUND) << blocked.result.message;
}

TEST(FootstepPlanner, ClimbsTwoStairsUpAndDown) {
  auto map = flat_map(2.2, 0.8, 0.01);
  add_box(map, 0.6, 0.0, 1.6, 0.8, 0.05);
  add_box(map, 0.9, 0.0, 1.3, 0.8, 0.10);
  FootstepPlanner planner(fast_params());
  const Footstep start = planner.stance_for_body({0.3, 0.4, 0.0}, Foot::kLeft);
  const FootstepPlan plan = planner.plan(map, start, {1.9, 0.4, 0.0});
  ASSERT_TRUE(plan.result.ok()) << plan.result.message;
  EXPECT_TRUE(uses(plan, "step_onto"));
  EXPECT_TRUE(uses(plan, "step_down"));
  double top = 0.0;
  for (const auto& s : plan.steps) top = std::max(top, s.z_m);
  EXPECT_NEAR(top, 0.10, 1e-5);
  EXPECT_NEAR(plan.steps.back().z_m, 0.0, 1e-6);
}

TEST(FootstepPlanner, LandingMarginKeepsTheToeOffARiserButNotOffADrop) {
  // From a left stance at x = 0.805 m, fwd_8 lands the right sole's toe at 0.965 m, half a
  // centimetre short of a rising step (cells from 0.97 m) or of a drop.
  const Footstep stance{{0.805, 0.405, 0.0}, 0.0, Foot::kLeft};
  const auto lands = [&](const FootstepPlanner& planner, const mapping::Heightmap& map, const std::string& action) {
    for (const auto& [name, foot] : planner.safe_steps(map, stance))
      if (name == action) return true;
    return false;
  };
  FootstepPlannerParams exact = fast_params(), margin = fast_params();
  margin.landing_margin_m = 0.015;
  const FootstepPlanner without(exact), with(margin);
  auto riser = flat_map(1.4, 0.8, 0.01);
  add_box(riser, 0.97, 0.0, 1.4, 0.8, 0.05);
  EXPECT_TRUE(lands(without, riser, "fwd_8"));
  EXPECT_FALSE(lands(with, riser, "fwd_8"));  // the toe would be within 1.5 cm of the riser
  EXPECT_TRUE(lands(with, riser, "fwd_4"));
  auto drop = flat_map(1.4, 0.8, 0.01);
  add_box(drop, 0.97, 0.0, 1.4, 0.8, -0.05);
  EXPECT_TRUE(lands(with, drop, "fwd_8"));  // an overhang of a few millimetres still supports the sole
  margin.landing_margin_m = -0.01;
  EXPECT_THROW(FootstepPlanner{margin}, ParamError);
}

TEST(FootstepPlanner, ClimbsTheScenarioStairsWithTheLoopsLandingMargin) {
  // nao_stairs: 35 cm treads, 5 cm risers; step_onto leaves 2 cm between the soles, so a 1 cm
  // margin still admits it from the right places.
  auto map = flat_map(2.6, 0.8, 0.01);
  add_box(map, 0.6, 0.0, 2.0, 0.8, 0.05);
  add_box(map, 0.95, 0.0, 1.65, 0.8, 0.10);
  FootstepPlannerParams p = fast_params();
  p.landing_margin_m = 0.01;
  FootstepPlanner planner(p);
  const FootstepPlan plan = planner.plan(map, planner.stance_for_body({0.3, 0.4, 0.0}, Foot::kLeft), {2.3, 0.4, 0.0});
  ASSERT_TRUE(plan.result.ok()) << plan.result.message;
  EXPECT_TRUE(uses(plan, "step_onto"));
  EXPECT_TRUE(uses(plan, "step_down"));
}

TEST(FootstepPlanner, ASwingFootStillOnTheStepAboveKeepsItsHeightOverTheEdge) {
  // nao_stairs seed 6 mid-way down: the left foot has stepped down onto the 5 cm tread, turned
  // by -0.39 rad, 2.4 cm in front of the 10 cm platform's edge (x = 1.65); the right foot is
  // still on the platform. The swing foot's via point beside the stance foot reaches 1.4 cm back
  // over the platform: taken at the stance height (peak 4 cm above 5 cm) it is 1 cm inside the
  // platform, so every planar step fails, and step_over / step_down land across the next
  // riser (x = 2.0). The swing foot really comes from the platform at its height and keeps it
  // until it drops onto the tread (sim::HumanoidWalker).
  auto map = flat_map(2.6, 0.8, 0.01);
  add_box(map, 0.6, 0.0, 2.0, 0.8, 0.05);
  add_box(map, 0.95, 0.0, 1.65, 0.8, 0.10);
  FootstepPlanner planner(fast_params());
  const double theta = -2.0 * 2.0 * std::numbers::pi / planner.params().theta_bins;  // on the lattice
  const Footstep stance{{1.765, 0.355, theta}, 0.05, Foot::kLeft};
  const Pose2 goal{2.3, 0.4, 0.0};
  const FootstepPlan assumed_level = planner.plan(map, stance, goal);
  EXPECT_EQ(assumed_level.result.outcome, Outcome::NO_PATH_FOUND) << assumed_level.result.message;
  EXPECT_TRUE(planner.safe_steps(map, stance).empty());
  // A swing foot at the stance height is the same problem.
  EXPECT_EQ(planner.plan(map, stance, goal, 0.05).result.outcome, Outcome::NO_PATH_FOUND);
  const FootstepPlan from_platform = planner.plan(map, stance, goal, 0.10);
  ASSERT_TRUE(from_platform.result.ok()) << from_platform.result.message;
  EXPECT_NEAR(from_platform.steps[1].z_m, 0.05, 1e-5);  // the right foot lands on the tread
  EXPECT_TRUE(uses(from_platform, "step_down"));
  EXPECT_NEAR(from_platform.steps.back().z_m, 0.0, 1e-6);
  EXPECT_FALSE(planner.safe_steps(map, stance, 0.10).empty());
  // Only the first step is lifted: a plan whose first step was not safe without the lift is not
  // valid from a stance whose swing foot is level with it.
  EXPECT_TRUE(planner.still_valid(map, from_platform, 0.10));
  EXPECT_FALSE(planner.still_valid(map, from_platform));
}

TEST(FootstepPlanner, TheStartFootLiftsOffWithoutALandingMargin) {
  // The same stance a centimetre further back (x = 1.745, seed 6's lattice cell) on a map that
  // reads the platform a centimetre longer (its edge cell high, as the run's Kalman map did):
  // the heel's corner is within half a cell of the edge. The lattice's inverse heightmaps sweep
  // a planned foot's lift-off over the cells within half a cell of its sole (a margin for where
  // it will land), which would leave only step_over; the start foot has landed and lifts off
  // within its own sole.
  auto map = flat_map(2.6, 0.8, 0.01);
  add_box(map, 0.6, 0.0, 2.0, 0.8, 0.05);
  add_box(map, 0.95, 0.0, 1.66, 0.8, 0.10);
  FootstepPlanner planner(fast_params());
  const double theta = -2.0 * 2.0 * std::numbers::pi / planner.params().theta_bins;
  const Footstep stance{{1.745, 0.355, theta}, 0.05, Foot::kLeft};
  std::vector<std::string> safe;
  for (const auto& [name, foot] : planner.safe_steps(map, stance, 0.10)) safe.push_back(name);
  for (const char* action : {"fwd_8", "diag_out", "long_out", "t_step", "step_over"})
    EXPECT_NE(std::find(safe.begin(), safe.end(), action), safe.end()) << action;
  const FootstepPlan plan = planner.plan(map, stance, {2.3, 0.4, 0.0}, 0.10);
  ASSERT_TRUE(plan.result.ok()) << plan.result.message;
  EXPECT_NEAR(plan.steps.back().z_m, 0.0, 1e-6);
}

TEST(FootstepPlanner, UnknownGroundNextToAPlatformDoesNotBlockTheHeuristic) {
  // Only a 10 cm platform across the whole width is known; the rest is unseen (free).
  mapping::Heightmap map({200, 100, 0.01, 0.0, 0.0});
  for (int y = 0; y < 100; ++y)
    for (int x = 50; x < 100; ++x) map.set(x, y, 0.10f, 1e-4f);
  const TerrainGrid terrain(map, 0.01);
  const Pose2 goal{1.5, 0.5, 0.0};
  const DijkstraHeuristic h(terrain, nao_action_set(), goal, 0.05);
  for (double x : {0.2, 0.75, 1.2}) EXPECT_TRUE(std::isfinite(h.seconds_to_goal(x, 0.5))) << x;
  // A 30 cm wall seen only from above, across the whole width, still blocks.
  mapping::Heightmap wall({200, 100, 0.01, 0.0, 0.0});
  for (int y = 0; y < 100; ++y)
    for (int x = 95; x < 100; ++x) wall.set(x, y, 0.30f, 1e-4f);
  const TerrainGrid walled(wall, 0.01);
  EXPECT_FALSE(std::isfinite(DijkstraHeuristic(walled, nao_action_set(), goal, 0.05).seconds_to_goal(0.2, 0.5)));
}

TEST(FootstepPlanner, TurnsSidewaysThroughAPassageNarrowerThanTheArms) {
  // Walls 0.5 m high leave a 0.24 m gap: the legs fit, the arms (0.29 m span) do not.
  auto map = flat_map(1.6, 1.2, 0.01);
  add_box(map, 0.7, 0.0, 0.9, 0.48, 0.5);
  add_box(map, 0.7, 0.72, 0.9, 1.2, 0.5);
  FootstepPlanner planner(fast_params());
  const Footstep start = planner.stance_for_body({0.3, 0.6, 0.0}, Foot::kLeft);
  const FootstepPlan plan = planner.plan(map, start, {1.3, 0.6, 0.0});
  ASSERT_TRUE(plan.result.ok()) << plan.result.message;
  bool sideways_in_gap = false;
  for (const auto& s : plan.steps) {
    if (s.pose.x > 0.72 && s.pose.x < 0.88) sideways_in_gap |= std::abs(std::sin(s.pose.theta)) > 0.85;
  }
  EXPECT_TRUE(sideways_in_gap);
}

TEST(FootstepPlanner, ReportsBlockedAndOffMapGoals) {
  auto map = flat_map(1.0, 1.0, 0.01);
  add_box(map, 0.6, 0.3, 0.9, 0.7, 0.3);
  FootstepPlanner planner(fast_params());
  const Footstep start = planner.stance_for_body({0.2, 0.5, 0.0}, Foot::kLeft);
  // A goal on top of a 30 cm block: the block top is flat, but no action climbs 30 cm.
  EXPECT_EQ(planner.plan(map, start, {0.75, 0.5, 0.0}).result.outcome, Outcome::NO_PATH_FOUND);
  add_box(map, 0.70, 0.45, 0.72, 0.55, 0.5);  // a spike under the goal stance
  EXPECT_EQ(planner.plan(map, start, {0.71, 0.5, 0.0}).result.outcome, Outcome::BLOCKED_GOAL);
  EXPECT_EQ(planner.plan(map, start, {3.0, 0.5, 0.0}).result.outcome, Outcome::PLAN_OUT_OF_MAP);
  EXPECT_EQ(planner.plan(map, start, {std::nan(""), 0.5, 0.0}).result.outcome, Outcome::INVALID_GOAL);
}

TEST(FootstepPlanner, DijkstraHeuristicIsAdmissibleAndAnytimeBoundHolds) {
  auto map = flat_map(1.0, 0.7, 0.01);
  add_box(map, 0.45, 0.0, 0.55, 0.4, 0.4);  // a wall to walk around
  FootstepPlannerParams p = params_with_bound(1.0);
  FootstepPlanner optimal(p);
  const Footstep start = optimal.stance_for_body({0.2, 0.25, 0.0}, Foot::kLeft);
  const Pose2 goal{0.8, 0.25, 0.0};
  const FootstepPlan best = optimal.plan(map, start, goal);
  ASSERT_TRUE(best.result.ok());
  const TerrainGrid terrain(map, 0.01);
  const DijkstraHeuristic h(terrain, nao_action_set(), goal, p.goal_tolerance_m);
  const Pose2 body{0.2, 0.25, 0.0};
  EXPECT_LE(h.seconds_to_goal(body.x, body.y), best.cost_s);
  EXPECT_GT(h.seconds_to_goal(body.x, body.y),
            EuclideanHeuristic(goal, p.goal_tolerance_m, 1e9).seconds_to_goal(0.2, 0.25));
  // Every published solution respects its epsilon bound against the optimum.
  p.search.initial_epsilon = 8.0;
  FootstepPlanner anytime(p);
  const FootstepPlan any = anytime.plan(map, start, goal);
  ASSERT_TRUE(any.result.ok());
  for (const auto& it : any.iterations) EXPECT_LE(it.cost, it.epsilon * best.cost_s + 1e-9);
  EXPECT_NEAR(any.cost_s, best.cost_s, 1e-9);
}

namespace {

// h at every state of an exact optimal plan (eps 1 with the Euclidean heuristic, which does not
// depend on the Dijkstra graph) never exceeds the remaining cost.
void expect_dijkstra_below_optimal(const mapping::Heightmap& map, const Pose2& start_body, const Pose2& goal) {
  FootstepPlannerParams p = params_with_bound(1.0);
  p.search.initial_epsilon = 1.0;
  p.heuristic = "euclidean";
  const FootstepPlanner optimal(p);
  const Footstep start = optimal.stance_for_body(start_body, Foot::kLeft);
  const FootstepPlan best = optimal.plan(map, start, goal);
  EXPECT_TRUE(best.result.ok()) << best.result.message;
  EXPECT_EQ(best.final_epsilon, 1.0);
  if (!best.result.ok() || best.final_epsilon != 1.0) return;
  const ActionSet set = nao_action_set();
  const TerrainGrid terrain(map, p.lattice_resolution_m);
  const DijkstraHeuristic h(terrain, set, goal, p.goal_tolerance_m);
  double remaining = best.cost_s;
  const double half = set.body.nominal_separation_m / 2.0;
  for (std::size_t i = 0; i < best.steps.size(); ++i) {
    const Footstep& f = best.steps[i];
    const Pose2 body = f.pose * Pose2{0.0, f.foot == Foot::kLeft ? -half : half, 0.0};
    EXPECT_LE(h.seconds_to_goal(body.x, body.y), remaining + 1e-9) << "step " << i;
    if (i < best.actions.size()) {
      for (const auto& a : set.actions)
        if (a.name == best.actions[i]) remaining -= a.duration_s;
    }
  }
  EXPECT_NEAR(remaining, 0.0, 1e-9);
}

}  // namespace

TEST(FootstepPlanner, DijkstraHeuristicStaysBelowExactOptimalCosts) {
  auto bar = flat_map(1.0, 0.6, 0.01);
  add_box(bar, 0.48, 0.0, 0.51, 0.6, 0.04);  // stepped over
  expect_dijkstra_below_optimal(bar, {0.2, 0.3, 0.0}, {0.8, 0.3, 0.0});
  auto platform = flat_map(1.0, 0.6, 0.01);
  add_box(platform, 0.45, 0.0, 1.0, 0.6, 0.03);  // stepped onto
  expect_dijkstra_below_optimal(platform, {0.2, 0.3, 0.0}, {0.8, 0.3, 0.0});
  auto blocks = flat_map(1.0, 0.9, 0.01);
  add_box(blocks, 0.45, 0.0, 0.55, 0.42, 0.4);  // a 7 cm gap between tall blocks, a way around
  add_box(blocks, 0.45, 0.49, 0.55, 0.75, 0.4);
  expect_dijkstra_below_optimal(blocks, {0.2, 0.45, 0.0}, {0.8, 0.45, 0.0});
}

TEST(FootstepPlanner, DijkstraHeuristicClosesAGapNarrowerThanTheBody) {
  // Two 40 cm blocks 6 cm apart: the point-robot graph passed between them, the body cannot
  // (its torso alone is 10 cm deep).
  auto map = flat_map(1.2, 1.4, 0.01);
  add_box(map, 0.5, 0.3, 0.7, 0.67, 0.4);
  add_box(map, 0.5, 0.73, 0.7, 1.1, 0.4);
  const TerrainGrid terrain(map, 0.01);
  const Pose2 goal{1.0, 0.7, 0.0};
  const DijkstraHeuristic h(terrain, nao_action_set(), goal, 0.05);
  EXPECT_GT(h.clearance_radius_m(), 0.04);
  EXPECT_TRUE(h.body_blocked(60, 70));   // the middle of the gap
  EXPECT_FALSE(h.body_blocked(20, 70));  // open floor
  EXPECT_FALSE(h.body_blocked(60, 20));  // beside the blocks
  // The distance goes around the blocks (at least 0.3 m off the line), not through the gap.
  const double through = 0.8, around = 2.0 * std::hypot(0.4, 0.4);
  const double d = h.distance_m(20, 70);
  EXPECT_GT(d, 0.9 * around);
  EXPECT_GT(d, through);
  // A start in a closed cell at the gap's mouth still gets a finite value from its open
  // neighbours (the start's own sole was never checked); the middle of the gap is cut off.
  int mouth = 40;
  while (mouth < 60 && !h.body_blocked(mouth, 70)) ++mouth;
  ASSERT_LT(mouth, 50);
  EXPECT_TRUE(std::isfinite(h.seconds_to_goal(0.01 * mouth + 0.005, 0.705)));
  EXPECT_FALSE(std::isfinite(h.seconds_to_goal(0.605, 0.705)));
}

TEST(FootstepPlanner, DijkstraDistanceIsAtMostTheStraightLineInTheOpen) {
  auto map = flat_map(1.5, 1.5, 0.01);
  const TerrainGrid terrain(map, 0.01);
  const Pose2 goal{0.105, 0.105, 0.0};  // cell (10, 10)
  const DijkstraHeuristic h(terrain, nao_action_set(), goal, 0.05);
  for (const auto& [dx, dy] : std::vector<std::pair<int, int>>{{100, 0}, {100, 24}, {100, 50}, {90, 70}, {80, 80}}) {
    const double straight = 0.01 * std::hypot(dx, dy), d = h.distance_m(10 + dx, 10 + dy);
    EXPECT_LE(d, straight + 1e-5) << dx << "," << dy;
    EXPECT_GE(d, straight / 1.0824 - 1e-5) << dx << "," << dy;
  }
}

TEST(FootstepPlanner, PlanBecomesInvalidWhenAnObstacleAppears) {
  auto map = flat_map(1.4, 0.8, 0.01);
  FootstepPlanner planner(fast_params());
  const Footstep start = planner.stance_for_body({0.3, 0.4, 0.0}, Foot::kLeft);
  const FootstepPlan plan = planner.plan(map, start, {1.1, 0.4, 0.0});
  ASSERT_TRUE(plan.result.ok());
  EXPECT_TRUE(planner.still_valid(map, plan));
  add_box(map, 0.6, 0.2, 0.75, 0.6, 0.3);
  EXPECT_FALSE(planner.still_valid(map, plan));
}

TEST(FootstepPlanner, RejectsBadParameters) {
  FootstepPlannerParams p;
  p.robot = "robby";
  EXPECT_THROW(FootstepPlanner{p}, ParamError);
  p = {};
  p.search.initial_epsilon = 0.5;
  EXPECT_THROW(FootstepPlanner{p}, ParamError);
}
