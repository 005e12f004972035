#include "bipednav/planning/footstep/terrain_generator.hpp"

#include <gtest/gtest.h>

using namespace bipednav;
using namespace bipednav::planning::footstep;

TEST(TerrainGenerator, DeterministicClutterWithValidProblems) {
  TerrainGeneratorParams p;
  p.resolution_m = 0.01;
  const auto a = random_terrain(p, 7), b = random_terrain(p, 7), c = random_terrain(p, 8);
  EXPECT_EQ(a.heights(), b.heights());
  EXPECT_NE(a.heights(), c.heights());
  float top = 0.0f;
  for (float h : a.heights()) top = std::max(top, h);
  EXPECT_GE(top, p.block_height_min_m);
  EXPECT_LE(top, p.block_height_max_m);
  const FootstepPlanner planner(FootstepPlannerParams{});
  const auto problems = random_problems(a, planner, 5, 1.5, 3.0, 3);
  ASSERT_EQ(problems.size(), 5u);
  for (const auto& pr : problems) {
    const double d = distance(pr.start, pr.goal);
    EXPECT_GE(d, 1.5);
    EXPECT_LE(d, 3.0);
  }
}

TEST(TerrainGenerator, RejectsBadParameters) {
  TerrainGeneratorParams p;
  p.size_m = 0.0;
  EXPECT_THROW(random_terrain(p, 1), ParamError);
}
