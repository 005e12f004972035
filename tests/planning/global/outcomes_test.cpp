#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"
#include "bipednav/planning/global/global_planner_factory.hpp"
#include "test_grids.hpp"

using namespace bipednav;
using namespace bipednav::planning::global;
using planning::global::test::centre;
using planning::global::test::expect_valid_path;
using planning::global::test::make_map;

namespace {

class Outcomes : public ::testing::TestWithParam<std::string> {
 protected:
  std::unique_ptr<GlobalPlanner> planner(const GlobalPlannerParams& p = {}) {
    return make_global_planner(GetParam(), p);
  }
};

bool mentions(const Result& r, const std::string& text) { return r.message.find(text) != std::string::npos; }

TEST_P(Outcomes, SuccessPathRunsFromStartPoseToGoalPose) {
  auto map = make_map(10, 6, 0.5);
  const Pose2 start{0.3, 0.4, 0.7}, goal{4.6, 2.6, -1.2};
  const PlanResult r = planner()->plan(map, start, goal, {});
  ASSERT_EQ(r.result.outcome, Outcome::SUCCESS) << r.result.message;
  expect_valid_path(map, r, {}, {0, 0}, {9, 5});
  // 5 diagonal and 4 straight moves of 0.5 m on free cells.
  EXPECT_NEAR(r.cost, 0.5 * (5 * std::sqrt(2.0) + 4), 1e-6);
  EXPECT_GT(r.expansions, 0u);
  EXPECT_GE(r.time_ms, 0.0);
  const auto& poses = r.path.poses;
  ASSERT_EQ(poses.size(), r.cells.size());
  EXPECT_DOUBLE_EQ(poses.front().x, start.x);
  EXPECT_DOUBLE_EQ(poses.front().theta, start.theta);
  EXPECT_DOUBLE_EQ(poses.back().x, goal.x);
  EXPECT_DOUBLE_EQ(poses.back().theta, goal.theta);
  for (std::size_t i = 1; i + 1 < poses.size(); ++i) {
    EXPECT_NEAR(poses[i].theta, std::atan2(poses[i + 1].y - poses[i].y, poses[i + 1].x - poses[i].x), 1e-12);
    const auto c = map.geometry().cell_center(r.cells[i]);
    EXPECT_DOUBLE_EQ(poses[i].x, c.x());
    EXPECT_DOUBLE_EQ(poses[i].y, c.y());
  }
}

TEST_P(Outcomes, CellCostsWeighTheMoves) {
  // One row: every move enters and leaves cells of cost 126, factor 1 + 2 * 126 / 252 = 2.
  auto map = make_map(5, 1, 1.0, 126);
  GlobalPlannerParams p;
  p.cost.cost_weight = 2.0;
  const PlanResult r = planner(p)->plan(map, centre(map, 0, 0), centre(map, 4, 0), {});
  ASSERT_TRUE(r.result.ok());
  EXPECT_DOUBLE_EQ(r.cost, 8.0);
}

TEST_P(Outcomes, AvoidsExpensiveCellsWhenCheaper) {
  auto map = make_map(7, 3, 1.0);
  for (int x = 1; x < 6; ++x) map.set_cost(x, 1, 252);  // a costly middle row, free rows around it
  const PlanResult r = planner()->plan(map, centre(map, 0, 1), centre(map, 6, 1), {});
  ASSERT_TRUE(r.result.ok());
  for (std::size_t i = 1; i + 1 < r.cells.size(); ++i) EXPECT_NE(r.cells[i].y, 1);
}

TEST_P(Outcomes, NoCornerCutting) {
  // Diagonal neighbours whose two side cells are lethal: no path.
  auto map = make_map(2, 2, 1.0);
  map.set_cost(1, 0, mapping::kLethal);
  map.set_cost(0, 1, mapping::kLethal);
  const PlanResult r = planner()->plan(map, centre(map, 0, 0), centre(map, 1, 1), {});
  EXPECT_EQ(r.result.outcome, Outcome::NO_PATH_FOUND);
  // With one side cell free the diagonal is still forbidden: the path goes around it (2 moves).
  map.set_cost(0, 1, mapping::kFree);
  const PlanResult r2 = planner()->plan(map, centre(map, 0, 0), centre(map, 1, 1), {});
  ASSERT_TRUE(r2.result.ok());
  EXPECT_DOUBLE_EQ(r2.cost, 2.0);
}

TEST_P(Outcomes, NoPathFound) {
  auto map = make_map(9, 9, 1.0);
  for (int y = 0; y < 9; ++y) map.set_cost(4, y, mapping::kInscribed);
  const PlanResult r = planner()->plan(map, centre(map, 1, 1), centre(map, 7, 7), {});
  EXPECT_EQ(r.result.outcome, Outcome::NO_PATH_FOUND);
  EXPECT_TRUE(mentions(r.result, "no path from start cell (1, 1) to goal cell (7, 7)")) << r.result.message;
  EXPECT_TRUE(r.path.empty());
}

TEST_P(Outcomes, BlockedStart) {
  auto map = make_map(5, 5, 1.0);
  map.set_cost(0, 0, mapping::kLethal);
  const PlanResult r = planner()->plan(map, centre(map, 0, 0), centre(map, 4, 4), {});
  EXPECT_EQ(r.result.outcome, Outcome::BLOCKED_START);
  EXPECT_TRUE(mentions(r.result, "start cell (0, 0) has cost 254 (lethal)")) << r.result.message;

  map.set_cost(0, 0, mapping::kInscribed);
  GlobalPlannerParams strict;
  strict.allow_start_in_inscribed = false;
  const PlanResult r2 = planner(strict)->plan(map, centre(map, 0, 0), centre(map, 4, 4), {});
  EXPECT_EQ(r2.result.outcome, Outcome::BLOCKED_START);
  EXPECT_TRUE(mentions(r2.result, "inscribed")) << r2.result.message;
  EXPECT_TRUE(mentions(r2.result, "allow_start_in_inscribed is false")) << r2.result.message;
}

TEST_P(Outcomes, InscribedStartMayBeLeftByDefault) {
  auto map = make_map(6, 6, 1.0);
  for (const auto& c : {mapping::Cell{0, 0}, {1, 0}, {2, 0}, {0, 1}, {0, 2}}) map.set_cost(c, mapping::kLethal);
  map.set_cost(1, 1, mapping::kInscribed);  // the robot stands close to the obstacles
  map.set_cost(1, 2, mapping::kInscribed);
  // The start may be left, the other inscribed cell stays impassable: the only way out is east
  // ((2, 2) would cut the corner of (1, 2)).
  const PlanResult r = planner()->plan(map, centre(map, 1, 1), centre(map, 5, 5), {});
  ASSERT_EQ(r.result.outcome, Outcome::SUCCESS) << r.result.message;
  expect_valid_path(map, r, {}, {1, 1}, {5, 5});
  ASSERT_GE(r.cells.size(), 2u);
  EXPECT_EQ(r.cells[1], (mapping::Cell{2, 1}));
  for (std::size_t i = 1; i < r.cells.size(); ++i) EXPECT_NE(r.cells[i], (mapping::Cell{1, 2}));
}

TEST_P(Outcomes, BlockedGoal) {
  auto map = make_map(5, 5, 1.0);
  map.set_cost(4, 4, mapping::kLethal);
  auto p = planner();
  PlanResult r = p->plan(map, centre(map, 0, 0), centre(map, 4, 4), {});
  EXPECT_EQ(r.result.outcome, Outcome::BLOCKED_GOAL);
  EXPECT_TRUE(mentions(r.result, "goal cell (4, 4) has cost 254 (lethal)")) << r.result.message;
  map.set_cost(4, 4, mapping::kInscribed);
  r = p->plan(map, centre(map, 0, 0), centre(map, 4, 4), {});
  EXPECT_EQ(r.result.outcome, Outcome::BLOCKED_GOAL);
  EXPECT_TRUE(mentions(r.result, "inscribed")) << r.result.message;
  map.set_cost(4, 4, mapping::kUnknown);
  r = p->plan(map, centre(map, 0, 0), centre(map, 4, 4), {});
  EXPECT_EQ(r.result.outcome, Outcome::SUCCESS) << "unknown cells are traversable by default";
  GlobalPlannerParams cautious;
  cautious.cost.unknown_is_obstacle = true;
  r = planner(cautious)->plan(map, centre(map, 0, 0), centre(map, 4, 4), {});
  EXPECT_EQ(r.result.outcome, Outcome::BLOCKED_GOAL);
  EXPECT_TRUE(mentions(r.result, "unknown")) << r.result.message;
}

// GlobalPlannerParams::goal_tolerance_m: an inscribed goal is planned to the nearest traversable
// cell within the tolerance, and the path still ends at the goal pose; lethal goals and goals with
// no such cell stay BLOCKED_GOAL.
TEST_P(Outcomes, InscribedGoalIsPlannedToTheNearestFreeCellWithinTheTolerance) {
  auto map = make_map(12, 8, 0.05);  // 0.05 m cells, as the global map
  // A wall at column 11 with its inscribed band on columns 8-10; the goal in cell (9, 4), 0.08 m
  // from the centre of cell (7, 4), the nearest free one ((7, 3) and (7, 5): 0.094 m).
  for (int y = 0; y < 8; ++y) {
    map.set_cost(11, y, mapping::kLethal);
    for (int x = 8; x <= 10; ++x) map.set_cost(x, y, mapping::kInscribed);
  }
  const Pose2 goal{0.455, 0.225, 0.4};
  GlobalPlannerParams p;
  p.goal_tolerance_m = 0.1;
  const PlanResult r = planner(p)->plan(map, centre(map, 1, 4), goal, {});
  ASSERT_EQ(r.result.outcome, Outcome::SUCCESS) << r.result.message;
  ASSERT_FALSE(r.cells.empty());
  EXPECT_EQ(r.cells.back(), (mapping::Cell{7, 4}));
  EXPECT_NEAR(r.cost, 6 * 0.05, 1e-9);  // six straight moves from column 1 to column 7
  const auto& poses = r.path.poses;
  ASSERT_GE(poses.size(), 2u);
  EXPECT_DOUBLE_EQ(poses.back().x, goal.x);
  EXPECT_DOUBLE_EQ(poses.back().y, goal.y);
  EXPECT_DOUBLE_EQ(poses.back().theta, goal.theta);
  const auto c = map.geometry().cell_center(7, 4);
  EXPECT_DOUBLE_EQ(poses[poses.size() - 2].x, c.x());  // the substitute cell comes before the goal
  EXPECT_DOUBLE_EQ(poses[poses.size() - 2].y, c.y());
  ASSERT_EQ(goal_search_cell(map, goal, p), (mapping::Cell{7, 4}));

  // A tighter tolerance than the 0.08 m: blocked, and the message says why.
  p.goal_tolerance_m = 0.07;
  PlanResult blocked = planner(p)->plan(map, centre(map, 1, 4), goal, {});
  EXPECT_EQ(blocked.result.outcome, Outcome::BLOCKED_GOAL);
  EXPECT_TRUE(mentions(blocked.result, "no traversable cell lies within goal_tolerance_m = 0.070 m"))
      << blocked.result.message;
  p.goal_tolerance_m = 0.0;  // off: every inscribed goal is blocked
  blocked = planner(p)->plan(map, centre(map, 1, 4), goal, {});
  EXPECT_EQ(blocked.result.outcome, Outcome::BLOCKED_GOAL);
  EXPECT_FALSE(mentions(blocked.result, "goal_tolerance_m")) << blocked.result.message;

  // A lethal goal cell is blocked whatever the tolerance.
  p.goal_tolerance_m = 1.0;
  blocked = planner(p)->plan(map, centre(map, 1, 4), centre(map, 11, 4), {});
  EXPECT_EQ(blocked.result.outcome, Outcome::BLOCKED_GOAL);
  EXPECT_TRUE(mentions(blocked.result, "254 (lethal)")) << blocked.result.message;
  EXPECT_FALSE(goal_search_cell(map, centre(map, 11, 4), p).has_value());

  p.goal_tolerance_m = -0.1;
  EXPECT_THROW(p.validate(), ParamError);
}

TEST_P(Outcomes, OutOfMap) {
  mapping::GridGeometry g;
  g.width = 10;
  g.height = 10;
  g.resolution_m = 0.5;
  g.origin_x_m = -2.0;
  g.origin_y_m = 1.0;
  const mapping::Costmap2D map(g);
  auto p = planner();
  PlanResult r = p->plan(map, {-2.5, 2.0, 0.0}, {1.0, 3.0, 0.0}, {});
  EXPECT_EQ(r.result.outcome, Outcome::PLAN_OUT_OF_MAP);
  EXPECT_TRUE(mentions(r.result,
                       "start (-2.500, 2.000) m is outside the map (x in [-2.000, 3.000) m, y in "
                       "[1.000, 6.000) m)"))
      << r.result.message;
  r = p->plan(map, {0.0, 2.0, 0.0}, {0.0, 6.0, 0.0}, {});
  EXPECT_EQ(r.result.outcome, Outcome::PLAN_OUT_OF_MAP);
  EXPECT_TRUE(mentions(r.result, "goal (0.000, 6.000) m is outside the map")) << r.result.message;
  r = p->plan(map, {std::numeric_limits<double>::quiet_NaN(), 2.0, 0.0}, {1.0, 3.0, 0.0}, {});
  EXPECT_EQ(r.result.outcome, Outcome::PLAN_OUT_OF_MAP);
  EXPECT_TRUE(mentions(r.result, "start pose is not finite")) << r.result.message;
  r = p->plan(mapping::Costmap2D{}, {0.0, 0.0, 0.0}, {1.0, 1.0, 0.0}, {});
  EXPECT_EQ(r.result.outcome, Outcome::PLAN_OUT_OF_MAP);
  EXPECT_TRUE(mentions(r.result, "the map is empty")) << r.result.message;
  // A valid request afterwards still works (the planner recovers its state).
  r = p->plan(map, {0.0, 2.0, 0.0}, {1.0, 3.0, 0.0}, {});
  EXPECT_TRUE(r.result.ok()) << r.result.message;
}

TEST_P(Outcomes, TimeLimitExceeded) {
  auto map = make_map(600, 600, 0.1);
  for (int y = 0; y < 580; ++y) map.set_cost(300, y, mapping::kLethal);  // forces a long search
  GlobalPlannerParams p;
  p.max_planning_time_ms = 1e-6;
  const PlanResult r = planner(p)->plan(map, centre(map, 10, 10), centre(map, 590, 10), {});
  EXPECT_EQ(r.result.outcome, Outcome::PLAN_PAT_EXCEEDED);
  EXPECT_TRUE(mentions(r.result, "planning time limit of 0.000 ms exceeded after")) << r.result.message;
  EXPECT_TRUE(r.path.empty());
}

TEST_P(Outcomes, StartEqualsGoal) {
  auto map = make_map(4, 4, 1.0);
  const PlanResult r = planner()->plan(map, {1.2, 1.3, 0.1}, {1.7, 1.8, 2.0}, {});
  ASSERT_TRUE(r.result.ok()) << r.result.message;
  EXPECT_DOUBLE_EQ(r.cost, 0.0);
  ASSERT_EQ(r.path.size(), 2u);
  EXPECT_DOUBLE_EQ(r.path.poses.back().theta, 2.0);
}

// A 0.8 m gap between two obstacle cells (0.1 m cells, inflated for a 0.38 m inscribed radius):
// its middle cells lie 0.4 m from both, open to the inscribed radius alone and closed to a
// clearance of 0.42 m (2 x 0.02 m sigma): NO_PATH_FOUND.
TEST_P(Outcomes, GapNarrowerThanThePlanningClearanceIsClosed) {
  auto obstacles = make_map(30, 30, 0.1);
  for (int y = 0; y < 30; ++y)
    if (y <= 10 || y >= 18) obstacles.set_cost(15, y, mapping::kLethal);
  const mapping::InflationParams inflation{0.38, 0.83, 3.0};
  mapping::Costmap2D map = obstacles;
  mapping::Inflator(inflation, 0.1).inflate(obstacles, map);
  ASSERT_EQ(map.cost(15, 14), mapping::inflation_cost(0.4, inflation));  // 237: 0.4 m from both sides
  const Pose2 start = centre(map, 3, 14), goal = centre(map, 27, 14);
  GlobalPlannerParams p;
  const PlanResult open = planner(p)->plan(map, start, goal, {});
  ASSERT_EQ(open.result.outcome, Outcome::SUCCESS) << open.result.message;
  p.cost.min_impassable_cost = min_impassable_cost(0.38 + 2 * 0.02, inflation);
  EXPECT_EQ(p.cost.min_impassable_cost, 224);  // 252 exp(-3 x 0.04) = 223.5
  const PlanResult closed = planner(p)->plan(map, start, goal, {});
  EXPECT_EQ(closed.result.outcome, Outcome::NO_PATH_FOUND) << closed.result.message;
}

INSTANTIATE_TEST_SUITE_P(BothPlanners, Outcomes, ::testing::Values("dstar_lite", "astar"));

TEST(GlobalPlannerFactory, ExplicitTableAndUnknownName) {
  EXPECT_EQ(make_global_planner("dstar_lite", {})->name(), "dstar_lite");
  EXPECT_EQ(make_global_planner("astar", {})->name(), "astar");
  EXPECT_EQ(global_planner_names(), (std::vector<std::string>{"dstar_lite", "astar"}));
  try {
    make_global_planner("navfn", {});
    FAIL();
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("dstar_lite | astar (got 'navfn')"), std::string::npos) << e.what();
  }
}

TEST(GlobalPlannerParams, ValidateRejectsNonsense) {
  GlobalPlannerParams p;
  p.max_planning_time_ms = -1.0;
  EXPECT_THROW(p.validate(), ParamError);
  p = {};
  p.cost.cost_weight = std::nan("");
  EXPECT_THROW(p.validate(), ParamError);
  p = {};
  p.cost.unknown_cost = 253;
  EXPECT_THROW(make_global_planner("astar", p), ParamError);
}

}  // namespace
