#include "bipednav/mapping/global_costmap.hpp"

#include <gtest/gtest.h>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"

using namespace bipednav::mapping;
using bipednav::Pose2;

namespace {

void expect_same(const ChangeSet& got, const ChangeSet& expect) {
  ASSERT_EQ(got.size(), expect.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].cell, expect[i].cell);
    EXPECT_EQ(got[i].old_cost, expect[i].old_cost);
    EXPECT_EQ(got[i].new_cost, expect[i].new_cost);
  }
}

Observation random_obs(bipednav::Rng& rng, const Eigen::Vector2d& c, int n) {
  Observation obs;
  obs.origin_map = {c.x(), c.y(), 0.8};
  for (int i = 0; i < n; ++i)
    obs.points_map.emplace_back(float(c.x() + rng.uniform(-7, 7)), float(c.y() + rng.uniform(-7, 7)), 0.5f);
  return obs;
}

}  // namespace

TEST(GlobalCostmap, ChangeSetsEqualBruteForceDiff) {
  for (const char* mode : {"free", "unknown", "lethal"}) {
    bipednav::Rng rng(11);
    GlobalCostmapParams p;
    p.unknown_cost_mode = mode;
    p.default_size_m = 12.0;
    GlobalCostmap global(GlobalCostmap::default_geometry({0.0, 0.0, 0.0}, p), p);
    LocalCostmapParams lp;
    lp.size_m = 4.0;
    LocalCostmap local(lp);
    for (int step = 0; step < 25; ++step) {
      const Pose2 pose{rng.uniform(-4, 4), rng.uniform(-4, 4), 0.0};
      std::vector<Observation> obs{random_obs(rng, pose.position(), 40)};
      obs[0].clearing = rng.bernoulli(0.7);
      local.update(pose, {random_obs(rng, pose.position(), 30)});
      const Costmap2D before = global.costmap();
      const ChangeSet ch = global.update(pose, obs, rng.bernoulli(0.7) ? &local : nullptr);
      expect_same(ch, diff(before, global.costmap()));
      if (step == 20) {
        const Costmap2D b2 = global.costmap();
        const ChangeSet cleared = global.clear();
        expect_same(cleared, diff(b2, global.costmap()));
      }
    }
  }
}

TEST(GlobalCostmap, UnknownCostModes) {
  for (const auto& [mode, cost] : {std::pair{"free", kFree}, {"unknown", kUnknown}, {"lethal", kLethal}}) {
    GlobalCostmapParams p;
    p.unknown_cost_mode = mode;
    GlobalCostmap global({50, 50, 0.1, 0.0, 0.0}, p);
    EXPECT_EQ(global.costmap().cost(10, 10), cost) << mode;
    Observation obs;
    obs.origin_map = {0.55, 2.55, 0.5};
    obs.points_map = {{4.05f, 2.55f, 0.5f}};
    global.update({0.55, 2.55, 0.0}, {obs}, nullptr);
    EXPECT_EQ(global.costmap().cost(40, 25), kLethal);
    EXPECT_EQ(global.occupancy().cost(20, 25), kFree);  // on the ray
    EXPECT_EQ(global.costmap().cost(20, 25), kFree);
    EXPECT_EQ(global.costmap().cost(38, 25), kInscribed);  // 0.2 m from the obstacle
    EXPECT_EQ(global.costmap().cost(10, 40), cost);
  }
  GlobalCostmapParams bad;
  bad.unknown_cost_mode = "maybe";
  EXPECT_THROW(GlobalCostmap({10, 10, 0.1, 0.0, 0.0}, bad), bipednav::ParamError);
}

TEST(GlobalCostmap, MergesLocalObstaclesAndFreeCells) {
  GlobalCostmap global({200, 200, 0.1, -10.0, -10.0});
  // A wall seen by the LiDAR long ago.
  Observation far;
  far.origin_map = {0, 0, 0.5};
  far.clearing = false;
  far.points_map = {{1.05f, 0.05f, 0.5f}, {8.05f, 0.05f, 0.5f}};
  global.update({0, 0, 0}, {far}, nullptr);
  EXPECT_EQ(global.occupancy().cost(110, 100), kLethal);
  // The local map now sees (1.05, 0.05) free and an obstacle at (-1.0, 0.5).
  LocalCostmap local;
  Observation near;
  near.origin_map = {0, 0, 0.5};
  near.points_map = {{-1.0f, 0.5f, 0.5f}, {2.0f, 0.05f, 0.5f}};
  local.update({0, 0, 0}, {near});
  global.update({0, 0, 0}, {}, &local);
  EXPECT_EQ(global.occupancy().cost(110, 100), kFree);
  EXPECT_EQ(global.occupancy().cost(90, 105), kLethal);
  EXPECT_EQ(global.occupancy().cost(180, 100), kLethal);  // outside the window: kept
}

TEST(GlobalCostmap, PriorMapAndBadInput) {
  GlobalCostmap global({20, 20, 0.1, 0.0, 0.0});
  Costmap2D prior({20, 20, 0.1, 0.0, 0.0}, kFree);
  prior.set_cost(5, 5, kLethal);
  const ChangeSet ch = global.set_occupancy(prior);
  EXPECT_FALSE(ch.empty());
  EXPECT_EQ(global.costmap().cost(5, 5), kLethal);
  EXPECT_THROW(global.set_occupancy(Costmap2D({10, 10, 0.1, 0.0, 0.0})), bipednav::Error);
  EXPECT_THROW(global.update({0, std::nan(""), 0}, {}, nullptr), bipednav::Error);
  EXPECT_THROW(GlobalCostmap({0, 10, 0.1, 0.0, 0.0}), bipednav::ParamError);
}

TEST(GlobalCostmap, LidarClearingCanBeDisabled) {
  for (bool clearing : {true, false}) {
    GlobalCostmapParams p;
    p.lidar_clearing = clearing;
    GlobalCostmap global({50, 50, 0.1, 0.0, 0.0}, p);
    Observation obs;
    obs.origin_map = {0.55, 2.55, 0.5};
    obs.points_map = {{2.05f, 2.55f, 0.5f}};
    global.update({0.55, 2.55, 0.0}, {obs}, nullptr);
    obs.points_map = {{4.05f, 2.55f, 0.5f}};  // the first obstacle moved away
    global.update({0.55, 2.55, 0.0}, {obs}, nullptr);
    EXPECT_EQ(global.occupancy().cost(20, 25), clearing ? kFree : kLethal);
    EXPECT_EQ(global.occupancy().cost(40, 25), kLethal);
  }
}
