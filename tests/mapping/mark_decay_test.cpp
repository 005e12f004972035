// Decay of obstacle marks (ObstacleLayerParams::mark_lifetime_updates) with and without heights.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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

// A LiDAR sweep from (0, 0, 1.47) to returns on a circle of radius `r` at height `z`, every
// direction (no marking): every cell within r is passed, at 1.47 - 0.57 * d / r m at distance d.
Observation sweep(float r = 2.4f, float z = 0.9f) {
  Observation obs;
  obs.origin_map = {0, 0, 1.47};
  obs.marking = false;
  for (int i = 0; i < 2000; ++i) {
    const double a = 2.0 * M_PI * i / 2000;
    obs.points_map.emplace_back(r * std::cos(a), r * std::sin(a), z);
  }
  return obs;
}

// LiDAR returns (marking) from a wall along x = 2.0, |y| <= 1, at heights 0.6-1.2 m.
Observation wall_returns() {
  Observation obs;
  obs.origin_map = {0, 0, 1.47};
  for (float y = -1.0f; y <= 1.0f; y += 0.02f)
    for (float z : {0.6f, 0.9f, 1.2f}) obs.points_map.emplace_back(2.0f, y, z);
  return obs;
}

long count_cells(const Costmap2D& g, std::uint8_t v) { return std::count(g.data().begin(), g.data().end(), v); }

}  // namespace

TEST(MarkDecay, AMarkPassedUnconfirmedExpiresAfterItsLifetime) {
  ObstacleLayer layer({4.0, 5.0, true, 5});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {low_obstacle()});
  const long marked = count_cells(grid, kLethal);
  ASSERT_GE(marked, 6);
  const auto c = kGrid.world_to_cell(1.0, 0.0);
  ASSERT_TRUE(c);
  // Updates whose rays do not pass it (out of every sensor's view) do not age it.
  for (int i = 0; i < 50; ++i) layer.update(grid, {});
  EXPECT_EQ(count_cells(grid, kLethal), marked);
  EXPECT_EQ(layer.mark_age(c->x, c->y), 0);
  for (int i = 1; i <= 5; ++i) {  // five updates whose LiDAR rays pass over it: still there
    layer.update(grid, {sweep()});
    EXPECT_EQ(count_cells(grid, kLethal), marked) << "update " << i;
    EXPECT_EQ(layer.mark_age(c->x, c->y), i);
  }
  layer.update(grid, {});  // an update that passes nothing in between does not count
  EXPECT_EQ(count_cells(grid, kLethal), marked);
  const CellRect changed = layer.update(grid, {sweep()});  // the sixth pass: older than five
  EXPECT_EQ(count_cells(grid, kLethal), 0);
  EXPECT_EQ(grid.cost(c->x, c->y), kUnknown);  // not known any more, not seen free either
  EXPECT_TRUE(changed.contains(c->x, c->y));
  EXPECT_EQ(layer.mark_age(c->x, c->y), -1);
}

TEST(MarkDecay, ManyRaysInOneUpdateCountOnce) {
  ObstacleLayer layer({4.0, 5.0, true, 2});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {low_obstacle()});
  const long marked = count_cells(grid, kLethal);
  layer.update(grid, {sweep(), sweep(2.2f, 1.0f), sweep(2.0f, 1.1f)});
  layer.update(grid, {sweep(), sweep(2.2f, 1.0f)});
  EXPECT_EQ(count_cells(grid, kLethal), marked);
  layer.update(grid, {sweep()});
  EXPECT_EQ(count_cells(grid, kLethal), 0);
}

TEST(MarkDecay, AReObservedMarkSurvivesAndTheOthersGo) {
  ObstacleLayer layer({4.0, 5.0, true, 5});
  Costmap2D grid(kGrid, kUnknown);
  const auto kept = kGrid.world_to_cell(1.0, 0.5), gone = kGrid.world_to_cell(1.0, -0.5);
  ASSERT_TRUE(kept && gone);
  layer.update(grid, {point(1.0f, 0.5f), point(1.0f, -0.5f)});
  for (int i = 1; i <= 30; ++i) {  // the LiDAR passes both every update, a camera confirms one every 4th
    std::vector<Observation> obs{sweep()};
    if (i % 4 == 0) obs.push_back(point(1.0f, 0.5f));
    layer.update(grid, obs);
    if (i <= 5) {
      EXPECT_EQ(grid.cost(gone->x, gone->y), kLethal) << "update " << i;
    }
  }
  EXPECT_EQ(grid.cost(kept->x, kept->y), kLethal);
  EXPECT_EQ(layer.mark_age(kept->x, kept->y), 2);  // confirmed at update 28, passed at 29 and 30
  // Gone at update 6 (back to unknown); the later sweeps pass it as any unknown cell: free.
  EXPECT_EQ(grid.cost(gone->x, gone->y), kFree);
  EXPECT_EQ(layer.mark_age(gone->x, gone->y), -1);
}

TEST(MarkDecay, AWallSeenEverySweepNeverExpires) {
  // The global map's LiDAR marks expire too: the rays to the wall's returns pass each other's
  // cells at the wall's own heights (clearing them, then marking them again), and every sweep's
  // returns confirm it.
  ObstacleLayer layer({10.0, 12.0, true, 3});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {wall_returns()});
  const long marked = count_cells(grid, kLethal);
  ASSERT_GE(marked, 40);
  const auto c = kGrid.world_to_cell(2.0, 0.0);
  ASSERT_TRUE(c);
  // Rays to 1.3 m at 2.4 m pass 1.31-1.33 m over the wall's cells: each sweep passes and confirms them.
  for (int i = 0; i < 100; ++i) layer.update(grid, {wall_returns(), sweep(2.4f, 1.3f)});
  EXPECT_EQ(count_cells(grid, kLethal), marked);
  EXPECT_EQ(layer.mark_age(c->x, c->y), 0);
}

TEST(MarkDecay, ALowObstacleSurvivesTheLidarRaysUntilItsLifetime) {
  // Digit: VLP-16 at 1.47 m, returns from the far wall at 0.9 m pass 1.24 m over the cylinder.
  ObstacleLayer layer({4.0, 5.0, true, 20});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {low_obstacle()});
  const long marked = count_cells(grid, kLethal);
  ASSERT_GE(marked, 6);
  for (int i = 1; i <= 20; ++i) {
    layer.update(grid, {rays(1.47, 2.4f, 0.9f)});
    ASSERT_EQ(count_cells(grid, kLethal), marked) << "update " << i;
  }
  layer.update(grid, {rays(1.47, 2.4f, 0.9f)});
  EXPECT_EQ(count_cells(grid, kLethal), 0);

  // Without heights the first LiDAR sweep erases it (the 2D layer's behaviour).
  ObstacleLayer flat({4.0, 5.0, false, 20});
  Costmap2D flat_grid(kGrid, kUnknown);
  flat.update(flat_grid, {low_obstacle()});
  flat.update(flat_grid, {rays(1.47, 2.4f, 0.9f)});
  EXPECT_EQ(count_cells(flat_grid, kLethal), 0);
}

TEST(MarkDecay, RaysCrossingTheBandClearAtOnce) {
  // Inside a camera's view, rays to the floor behind the obstacle cross its heights: they free it
  // long before its lifetime (the frustum's negative evidence).
  ObstacleLayer layer({4.0, 5.0, true, 1000});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {low_obstacle()});
  ASSERT_GE(count_cells(grid, kLethal), 6);
  layer.update(grid, {rays(0.95, 1.6f, 0.0f)});  // 0.33-0.36 m high at x = 1.0-1.05 m
  EXPECT_EQ(count_cells(grid, kLethal), 0);
}

TEST(MarkDecay, ObstaclesSetElsewhereDoNotDecay) {
  ObstacleLayer layer({4.0, 5.0, true, 3});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {});
  // A prior map's wall with heights copied in (not reset): rays pass it, it does not decay.
  const auto c = kGrid.world_to_cell(1.0, 0.0);
  ASSERT_TRUE(c);
  grid.set_cost(c->x, c->y, kLethal);
  layer.include_band(grid, c->x, c->y, HeightBand{0.1f, 0.5f}, false);  // heights, but no decay
  for (int i = 0; i < 10; ++i) layer.update(grid, {sweep()});
  EXPECT_EQ(grid.cost(c->x, c->y), kLethal);
  EXPECT_EQ(layer.mark_age(c->x, c->y), -1);
  layer.update(grid, {low_obstacle()});  // a return in it does not make it expire either
  for (int i = 0; i < 10; ++i) layer.update(grid, {sweep()});
  EXPECT_EQ(grid.cost(c->x, c->y), kLethal);
}

TEST(MarkDecay, CopiedMarksKeepTheirAge) {
  ObstacleLayer layer({4.0, 5.0, true, 10});
  Costmap2D grid(kGrid, kUnknown);
  layer.update(grid, {});
  const auto c = kGrid.world_to_cell(1.0, 0.0);
  ASSERT_TRUE(c);
  grid.set_cost(c->x, c->y, kLethal);
  layer.include_band(grid, c->x, c->y, HeightBand{0.1f, 0.5f}, true, 0.7);  // 7 of 10 used
  EXPECT_EQ(layer.mark_age(c->x, c->y), 7);
  layer.include_band(grid, c->x, c->y, HeightBand{0.1f, 0.5f}, false, 0.9);  // older: no change
  EXPECT_EQ(layer.mark_age(c->x, c->y), 7);
  for (int i = 0; i < 3; ++i) layer.update(grid, {sweep()});
  EXPECT_EQ(layer.mark_age(c->x, c->y), 10);
  EXPECT_EQ(grid.cost(c->x, c->y), kLethal);
  layer.update(grid, {sweep()});
  EXPECT_EQ(grid.cost(c->x, c->y), kUnknown);
}

TEST(MarkDecay, RollingWindowCarriesTheAges) {
  LocalCostmapParams p;
  p.height_aware_clearing = true;
  p.mark_decay_s = 0.5;  // 5 updates at 10 Hz
  LocalCostmap local(p);
  local.update({0.0, 0.0, 0.0}, {low_obstacle()});
  const auto lethal = [&] { return count_cells(local.obstacles(), kLethal); };
  const long marked = lethal();
  ASSERT_GE(marked, 6);
  // The window moves with the robot; the LiDAR (kept at the origin here) passes over the obstacle.
  for (int i = 0; i < 5; ++i) local.update({0.1 * (i + 1), 0.0, 0.0}, {sweep()});
  EXPECT_EQ(lethal(), marked);
  local.update({0.6, 0.0, 0.0}, {sweep()});
  EXPECT_EQ(lethal(), 0);
}

TEST(MarkDecay, GlobalMapDecaysLidarAndMergedMarksPassedUnconfirmed) {
  LocalCostmapParams lp;
  lp.height_aware_clearing = true;
  lp.mark_decay_s = 0.4;  // 4 local updates
  LocalCostmap local(lp);
  GlobalCostmapParams gp;
  gp.height_aware_clearing = true;
  gp.mark_decay_s = 2.0;  // 4 global updates at 2 Hz
  GlobalCostmap global({100, 100, 0.1, -5.0, -5.0}, gp);
  const auto cost = [&](double x, double y) {
    const auto c = global.geometry().world_to_cell(x, y);
    return c ? global.occupancy().cost(c->x, c->y) : kFree;
  };

  // A cylinder only the local map's camera saw, passed over by two of the local map's LiDAR sweeps
  // (half its local lifetime used) before the global map first merges it.
  local.update({0, 0, 0}, {low_obstacle()});
  local.update({0, 0, 0}, {sweep(1.9f, 0.9f)});
  local.update({0, 0, 0}, {sweep(1.9f, 0.9f)});
  // The global LiDAR: a wall ahead (x = 2), a stale return at 0.9 m (a person who has left; outside
  // the local window), and one beyond the reach of the later rays.
  Observation first = wall_returns();
  first.points_map.emplace_back(4.5f, 0.0f, 0.9f);
  first.points_map.emplace_back(-4.75f, -4.75f, 1.0f);
  global.update({0, 0, 0}, {first}, &local);
  ASSERT_EQ(cost(2.0, 0.0), kLethal);
  ASSERT_EQ(cost(4.5, 0.0), kLethal);
  ASSERT_EQ(cost(-4.75, -4.75), kLethal);
  ASSERT_EQ(cost(1.02, 0.0), kLethal);

  // Every later sweep sees the wall and passes over the rest within 4.7 m.
  const auto later = [] { return std::vector<Observation>{wall_returns(), sweep(4.7f, 0.9f)}; };
  for (int i = 2; i <= 3; ++i) {
    global.update({0, 0, 0}, later(), nullptr);
    EXPECT_EQ(cost(1.02, 0.0), kLethal) << "global update " << i;
  }
  global.update({0, 0, 0}, later(), nullptr);
  EXPECT_EQ(cost(1.02, 0.0), kUnknown);  // 2 of 4 used when merged, then passed three times
  EXPECT_EQ(cost(4.5, 0.0), kLethal);    // passed three times
  global.update({0, 0, 0}, later(), nullptr);
  EXPECT_EQ(cost(4.5, 0.0), kLethal);
  global.update({0, 0, 0}, later(), nullptr);
  EXPECT_EQ(cost(4.5, 0.0), kUnknown);  // passed by five sweeps, never confirmed
  for (int i = 0; i < 20; ++i) global.update({0, 0, 0}, later(), nullptr);
  EXPECT_EQ(cost(2.0, 0.0), kLethal);      // confirmed by every sweep
  EXPECT_EQ(cost(-4.75, -4.75), kLethal);  // out of the LiDAR's reach: nothing says it has gone
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
