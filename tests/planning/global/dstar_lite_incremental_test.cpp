#include <gtest/gtest.h>

#include "bipednav/common/rng.hpp"
#include "bipednav/planning/global/dstar_lite_planner.hpp"
#include "bipednav/planning/global/global_planner_factory.hpp"
#include "test_grids.hpp"

using namespace bipednav;
using namespace bipednav::planning::global;
using planning::global::test::centre;
using planning::global::test::expect_valid_path;
using planning::global::test::make_map;

namespace {

std::uint8_t random_cost(Rng& rng) {
  const double u = rng.uniform();
  if (u < 0.45) return mapping::kFree;
  if (u < 0.70) return static_cast<std::uint8_t>(rng.uniform_int(1, 252));
  if (u < 0.88) return mapping::kLethal;
  if (u < 0.96) return mapping::kInscribed;
  return mapping::kUnknown;
}

struct PropertyCase {
  int width;
  int height;
  int iterations;
  bool unknown_is_obstacle;
  std::uint64_t seed;
};

// After every batch of random cell changes and start moves, D* Lite's repaired plan has the same
// outcome and cost as A* from scratch, and its path is valid.
void run_property(const PropertyCase& pc) {
  Rng rng(pc.seed);
  GlobalPlannerParams params;
  params.cost.unknown_is_obstacle = pc.unknown_is_obstacle;
  DStarLitePlanner dstar(params);
  auto astar = make_global_planner("astar", params);
  auto map = make_map(pc.width, pc.height, 0.1);
  for (auto& c : map.data()) c = rng.bernoulli(0.3) ? random_cost(rng) : mapping::kFree;
  auto rand_cell = [&] {
    return mapping::Cell{static_cast<int>(rng.uniform_int(0, pc.width - 1)),
                         static_cast<int>(rng.uniform_int(0, pc.height - 1))};
  };
  mapping::Cell start = rand_cell(), goal = rand_cell();
  int incremental = 0, solved = 0, changes_total = 0;
  for (int it = 0; it < pc.iterations; ++it) {
    mapping::ChangeSet changes;
    const int n = static_cast<int>(rng.uniform_int(0, 6));
    for (int i = 0; i < n; ++i) {
      mapping::Cell c = rand_cell();
      if (rng.bernoulli(0.5)) {  // near the robot, where discoveries happen
        c.x = std::clamp(start.x + static_cast<int>(rng.uniform_int(-4, 4)), 0, pc.width - 1);
        c.y = std::clamp(start.y + static_cast<int>(rng.uniform_int(-4, 4)), 0, pc.height - 1);
      }
      if (c == goal && rng.bernoulli(0.9)) continue;
      const std::uint8_t nc = random_cost(rng);
      changes.push_back({c, map.cost(c), nc});
      map.set_cost(c, nc);
    }
    changes_total += n;
    if (rng.bernoulli(0.05)) changes.resize(changes.size() / 2);  // an incomplete change set
    if (rng.bernoulli(0.7)) {
      start.x = std::clamp(start.x + static_cast<int>(rng.uniform_int(-1, 1)), 0, pc.width - 1);
      start.y = std::clamp(start.y + static_cast<int>(rng.uniform_int(-1, 1)), 0, pc.height - 1);
    } else if (rng.bernoulli(0.1)) {
      start = rand_cell();
    }
    if (rng.bernoulli(0.01)) goal = rand_cell();
    const Pose2 s = centre(map, start.x, start.y), g = centre(map, goal.x, goal.y, 1.0);
    const PlanResult rd = dstar.plan(map, s, g, changes);
    const PlanResult ra = astar->plan(map, s, g, changes);
    incremental += dstar.last_was_incremental();
    ASSERT_EQ(dstar.search().invariant_violations(), 0u) << "iteration " << it;
    ASSERT_EQ(rd.result.outcome, ra.result.outcome)
        << "iteration " << it << ": " << rd.result.message << " vs " << ra.result.message;
    if (!ra.result.ok()) continue;
    ++solved;
    ASSERT_DOUBLE_EQ(rd.cost, ra.cost) << "iteration " << it;  // integer costs: exactly equal
    expect_valid_path(map, rd, params, start, goal);
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GT(incremental, pc.iterations / 2);
  EXPECT_GT(solved, pc.iterations / 4);
  EXPECT_GT(changes_total, pc.iterations);
}

TEST(DStarLiteIncremental, MatchesAStarOnSmallRandomGrids) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) run_property({30, 24, 1500, false, seed});
}

TEST(DStarLiteIncremental, MatchesAStarWithUnknownAsObstacle) { run_property({40, 40, 1500, true, 11}); }

TEST(DStarLiteIncremental, MatchesAStarOnALargerGrid) { run_property({120, 90, 400, false, 21}); }

TEST(DStarLiteIncremental, RepairsWithFewerExpansionsThanTheFirstPlan) {
  // A varied cost field makes the first search expensive; a small obstacle appears on the path
  // just ahead of the robot, which has moved one cell.
  Rng rng(5);
  auto map = make_map(200, 200, 0.1);
  for (auto& c : map.data()) c = static_cast<std::uint8_t>(rng.uniform_int(0, 200));
  GlobalPlannerParams params;
  DStarLitePlanner dstar(params);
  const Pose2 goal = centre(map, 190, 150);
  const PlanResult first = dstar.plan(map, centre(map, 5, 5), goal, {});
  ASSERT_TRUE(first.result.ok());
  EXPECT_FALSE(dstar.last_was_incremental());
  const mapping::Cell robot = first.cells[1];
  const mapping::Cell ahead = first.cells[6];
  mapping::ChangeSet changes;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const mapping::Cell c{ahead.x + dx, ahead.y + dy};
      changes.push_back({c, map.cost(c), mapping::kLethal});
      map.set_cost(c, mapping::kLethal);
    }
  const Pose2 robot_pose = centre(map, robot.x, robot.y);
  const PlanResult second = dstar.plan(map, robot_pose, goal, changes);
  ASSERT_TRUE(second.result.ok());
  EXPECT_TRUE(dstar.last_was_incremental());
  EXPECT_EQ(dstar.last_missed_changes(), 0u);
  EXPECT_LT(second.expansions * 5, first.expansions);
  auto astar = make_global_planner("astar", params);
  EXPECT_DOUBLE_EQ(second.cost, astar->plan(map, robot_pose, goal, {}).cost);
  expect_valid_path(map, second, params, robot, {190, 150});
}

}  // namespace
