// Decay of obstacle marks (ObstacleLayerParams::mark_lifetime_updates) with and without heights.
#include <gtest/gtest.h>

#include <algorithm>

#include "bipednav/common/error.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/mapping/global_costmap.hpp"
#include "bipednav/mapping/local_costmap.hpp"
#include "bipednav/mapping/obstacle_layer.hpp"

using namespace bipednav::mapping;

namespace {

const GridGeometry kGrid{100, 100, 0.05, -2.5, -2.5};  // 5 m square around the origin

// Returns of a 0.3 m wide low obstacle at x = `x`, seen by a depth camera at 0.95 m at heights
// 0.1-0.5 m (a 0.5 m cylinder of turtlebot3_world).
Observation low_obstacle(float x = 1.0f) {
  Observation obs;
  obs.origin_map = {0, 0, 0.95};
  for (float y = -0.15f; y <= 0.15f; y += 0.02f)
    for (float z : {0.1f, 0.3f, 0.5f}) obs.points_map.emplace_back(x, y, z);
  return obs;
}

// One return at (x, y, z) seen from (0, 0, 0.95).
Observation point(float x, float y, float z = 0.3f) {
  Observation obs;
  obs.origin_map = {0, 0, 0.95};
  obs.points_map.emplace_back(x, y, z);
  return obs;
}

// Clearing rays from (0, 0, origin_z) to (x, y * x / 2.0, z) for y in [-0.3, 0.3] (no marking):
// they cross the cells of low_obstacle(1.0) on their way.
Observation rays(double origin_z, float x, float z) {
  Observation obs;
  obs.origin_map = {0, 0, origin_z};
  obs.marking = false;
  for (float y = -0.3f; y <= 0.3f; y += 0.005f) obs.points_map.emplace_back(x, y * x, z);
  return obs;
}

long count(const Costmap2D& g, std::uint8_t v) { return std::count(g.data().begin(), g.data().end(), v); }

}  // namespace

TEST(MarkDecay, AMarkNotConfirmedExpiresAfterItsLifetime) {
  ObstacleLayer layer({4.0, 5.0, false, 5});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {low_obstacle()});
  const long marked = count(grid, kLethal);
  ASSERT_GE(marked, 6);
  for (int i = 1; i <= 5; ++i) {  // five more updates that see nothing: still there
    layer.update(grid, {});
    EXPECT_EQ(count(grid, kLethal), marked) << "update " << i;
  }
  const auto c = kGrid.world_to_cell(1.0, 0.0);
  ASSERT_TRUE(c);
  EXPECT_EQ(layer.mark_age(c->x, c->y), 5);
  const CellRect changed = layer.update(grid, {});  // the sixth: older than five updates
  EXPECT_EQ(count(grid, kLethal), 0);
  EXPECT_EQ(grid.cost(c->x, c->y), kUnknown);  // not known any more, not seen free either
  EXPECT_TRUE(changed.contains(c->x, c->y));
}

TEST(MarkDecay, AReObservedMarkSurvivesAndTheOthersGo) {
  ObstacleLayer layer({4.0, 5.0, true, 5});
  Costmap2D grid(kGrid, kUnknown);
  const auto kept = kGrid.world_to_cell(1.0, 0.5), gone = kGrid.world_to_cell(1.0, -0.5);
  ASSERT_TRUE(kept && gone);
  layer.update(grid, {point(1.0f, 0.5f), point(1.0f, -0.5f)});
  for (int i = 1; i <= 30; ++i)
    layer.update(grid, i % 4 == 0 ? std::vector{point(1.0f, 0.5f)} : std::vector<Observation>{});
  EXPECT_EQ(grid.cost(kept->x, kept->y), kLethal);
  EXPECT_LE(layer.mark_age(kept->x, kept->y), 3);
  EXPECT_EQ(grid.cost(gone->x, gone->y), kUnknown);
  EXPECT_EQ(layer.mark_age(gone->x, gone->y), -1);
}

TEST(MarkDecay, ALowObstacleSurvivesTheLidarRaysUntilItsLifetime) {
  // Digit: VLP-16 at 1.47 m, returns from the far wall at 0.9 m pass 1.24 m over the cylinder.
  ObstacleLayer layer({4.0, 5.0, true, 20});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {low_obstacle()});
  const long marked = count(grid, kLethal);
  ASSERT_GE(marked, 6);
  for (int i = 1; i <= 20; ++i) {
    layer.update(grid, {rays(1.47, 2.4f, 0.9f)});
    ASSERT_EQ(count(grid, kLethal), marked) << "update " << i;
  }
  layer.update(grid, {rays(1.47, 2.4f, 0.9f)});
  EXPECT_EQ(count(grid, kLethal), 0);

  // Without heights the first LiDAR sweep erases it (the 2D layer's behaviour).
  ObstacleLayer flat({4.0, 5.0, false, 20});
  Costmap2D flat_grid(kGrid, kUnknown);
  flat.update(flat_grid, {low_obstacle()});
  flat.update(flat_grid, {rays(1.47, 2.4f, 0.9f)});
  EXPECT_EQ(count(flat_grid, kLethal), 0);
}

TEST(MarkDecay, RaysCrossingTheBandClearAtOnce) {
  // Inside a camera's view, rays to the floor behind the obstacle cross its heights: they free it
  // long before its lifetime (the frustum's negative evidence).
  ObstacleLayer layer({4.0, 5.0, true, 1000});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {low_obstacle()});
  ASSERT_GE(count(grid, kLethal), 6);
  layer.update(grid, {rays(0.95, 1.6f, 0.0f)});  // 0.33-0.36 m high at x = 1.0-1.05 m
  EXPECT_EQ(count(grid, kLethal), 0);
}

TEST(MarkDecay, PermanentMarksAndPriorMapsDoNotDecay) {
  ObstacleLayer layer({4.0, 5.0, true, 3});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {low_obstacle()}, true, false);  // marks_expire false (a global LiDAR)
  const long marked = count(grid, kLethal);
  const auto c = kGrid.world_to_cell(1.0, 0.0);
  ASSERT_TRUE(c);
  layer.update(grid, {low_obstacle()});  // confirmed by an expiring update: stays permanent
  for (int i = 0; i < 10; ++i) layer.update(grid, {});
  EXPECT_EQ(count(grid, kLethal), marked);
  EXPECT_EQ(layer.mark_age(c->x, c->y), -1);
  // An obstacle someone else wrote into the grid has no mark: it stays.
  grid.set_cost(10, 10, kLethal);
  for (int i = 0; i < 10; ++i) layer.update(grid, {});
  EXPECT_EQ(grid.cost(10, 10), kLethal);
}

TEST(MarkDecay, RollingWindowCarriesTheAges) {
  LocalCostmapParams p;
  p.height_aware_clearing = true;
  p.mark_decay_s = 0.5;  // 5 updates at 10 Hz
  LocalCostmap local(p);
  local.update({0.0, 0.0, 0.0}, {low_obstacle()});
  const auto lethal = [&] { return count(local.obstacles(), kLethal); };
  const long marked = lethal();
  ASSERT_GE(marked, 6);
  for (int i = 0; i < 5; ++i) local.update({0.1 * (i + 1), 0.0, 0.0}, {});  // the window moves with the robot
  EXPECT_EQ(lethal(), marked);
  local.update({0.6, 0.0, 0.0}, {});
  EXPECT_EQ(lethal(), 0);
}

TEST(MarkDecay, GlobalMapKeepsLidarMarksAndForgetsMergedOnesAfterTheLocalMap) {
  LocalCostmapParams lp;
  lp.height_aware_clearing = true;
  lp.mark_decay_s = 0.5;  // 5 local updates
  LocalCostmap local(lp);
  GlobalCostmapParams gp;
  gp.height_aware_clearing = true;
  gp.merged_mark_decay_s = 2.0;  // 4 global updates at 2 Hz
  GlobalCostmap global({100, 100, 0.1, -5.0, -5.0}, gp);
  const auto global_lethal = [&] { return count(global.occupancy(), kLethal); };

  local.update({0, 0, 0}, {low_obstacle()});
  Observation wall = point(-2.0f, 0.0f, 1.0f);  // a LiDAR return from a wall behind the robot
  wall.origin_map = {0, 0, 1.47};
  global.update({0, 0, 0}, {wall}, &local);
  const long merged = global_lethal();
  ASSERT_GE(merged, 3);
  const auto w = global.geometry().world_to_cell(-2.0, 0.0);
  ASSERT_TRUE(w);
  // While the local map holds the obstacle, the merges keep confirming it.
  for (int i = 0; i < 5; ++i) {
    local.update({0, 0, 0}, {});
    global.update({0, 0, 0}, {}, &local);
  }
  EXPECT_EQ(global_lethal(), merged);
  local.update({0, 0, 0}, {});  // the local map's sixth update without it: gone there
  EXPECT_EQ(count(local.obstacles(), kLethal), 0);
  for (int i = 0; i < 4; ++i) global.update({0, 0, 0}, {}, &local);
  EXPECT_EQ(global_lethal(), merged);  // four more global updates it still waits
  global.update({0, 0, 0}, {}, &local);
  EXPECT_EQ(global_lethal(), 1);  // only the LiDAR's wall return is left
  EXPECT_EQ(global.occupancy().cost(w->x, w->y), kLethal);
}

TEST(MarkDecay, WalkersGetHeightsAndDecayWheeledRobotsNeither) {
  bipednav::RobotProfile digit;
  digit.kind = "walker";
  if (!kWalkerHeightAwareMaps) GTEST_SKIP() << "walkers' height-aware maps are off by default";
  const auto dl = LocalCostmapParams::for_robot(digit);
  const auto dg = GlobalCostmapParams::for_robot(digit);
  EXPECT_TRUE(dl.height_aware_clearing && dg.height_aware_clearing);
  EXPECT_GT(dl.obstacle_layer().mark_lifetime_updates, 0);
  EXPECT_GT(dg.obstacle_layer().mark_lifetime_updates, 0);
  const auto tl = LocalCostmapParams::for_robot(bipednav::RobotProfile{});
  EXPECT_FALSE(tl.height_aware_clearing);
  EXPECT_EQ(tl.obstacle_layer().mark_lifetime_updates, 0);
}

TEST(MarkDecay, RejectsBadDecays) {
  LocalCostmapParams p;
  p.mark_decay_s = -1.0;
  EXPECT_THROW(LocalCostmap{p}, bipednav::ParamError);
  p.mark_decay_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(LocalCostmap{p}, bipednav::ParamError);
  EXPECT_THROW(ObstacleLayer({4.0, 5.0, false, -2}), bipednav::ParamError);
  EXPECT_EQ(decay_updates(0.05, 10.0), 1);  // a positive time keeps at least one update
  EXPECT_EQ(decay_updates(15.0, 10.0), 150);
}
