#include "bench/replan_benchmark.hpp"

#include <gtest/gtest.h>

using namespace bipednav;
using namespace bipednav::planning::global;
using namespace bipednav::bench;

namespace {

TEST(ThreeRoomsWorld, HasWallsDoorsAndHiddenObstacles) {
  const ThreeRoomsWorld w = make_three_rooms_world(0.1);
  EXPECT_EQ(w.truth.width(), 300);
  EXPECT_EQ(w.truth.height(), 60);
  const auto cell = [&](double x, double y) { return *w.truth.geometry().world_to_cell(x, y); };
  EXPECT_EQ(w.walls.cost(cell(10.0, 2.0)), mapping::kLethal);  // dividing wall
  EXPECT_EQ(w.walls.cost(cell(10.0, 5.0)), mapping::kFree);    // its door
  EXPECT_EQ(w.walls.cost(cell(20.0, 1.0)), mapping::kFree);    // the second door
  EXPECT_EQ(w.walls.cost(cell(5.5, 4.0)), mapping::kFree);     // unknown to the robot...
  EXPECT_EQ(w.truth.cost(cell(5.5, 4.0)), mapping::kLethal);   // ...but there
  EXPECT_EQ(w.truth.cost(cell(w.start.x, w.start.y)), mapping::kFree);
  EXPECT_EQ(w.truth.cost(cell(w.goal.x, w.goal.y)), mapping::kFree);
}

TEST(AdvanceAlong, InterpolatesAndClampsAtTheEnd) {
  Path p;
  p.poses = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}};
  const Pose2 a = advance_along(p, 1.5);
  EXPECT_DOUBLE_EQ(a.x, 1.0);
  EXPECT_DOUBLE_EQ(a.y, 0.5);
  EXPECT_NEAR(a.theta, M_PI / 2, 1e-12);
  const Pose2 b = advance_along(p, 10.0);
  EXPECT_DOUBLE_EQ(b.y, 2.0);
}

// The robot discovers the obstacles on its way: D* Lite's repaired plans equal A*'s from scratch
// at every replan, the robot reaches the goal, and repairs expand far fewer vertices.
TEST(ReplanBenchmark, DStarLiteRepairsMatchAStarAllTheWay) {
  ReplanBenchParams p;
  p.step_m = 0.3;  // fewer replans keep the test short
  const ReplanStats s = run_replan_benchmark(p);
  EXPECT_TRUE(s.reached_goal);
  EXPECT_EQ(s.cost_mismatches, 0);
  EXPECT_GT(s.replans, 80);
  EXPECT_GT(s.changed_cells, 1000u);
  EXPECT_GT(s.expansions_ratio, 10.0);
  // Both clocks are recorded (no timing goal here: that is the benchmark's).
  EXPECT_GT(s.dstar_cpu_mean_ms, 0.0);
  EXPECT_GT(s.astar_cpu_mean_ms, 0.0);
  EXPECT_GT(s.cpu_time_ratio, 0.0);
}

}  // namespace
