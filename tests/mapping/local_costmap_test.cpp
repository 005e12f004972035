#include "bipednav/mapping/local_costmap.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"
#include "bipednav/mapping/global_costmap.hpp"

using namespace bipednav::mapping;
using bipednav::Pose2;

namespace {

// Returns of a horizontal scan from `origin` against axis-aligned boxes (2D, z = 0.5), one ray
// per `step_rad`; rays that hit nothing return a point at `far_m`.
struct Box {
  double x0, y0, x1, y1;
};
Observation scan(const Eigen::Vector2d& origin, const std::vector<Box>& boxes, double far_m = 3.9) {
  Observation obs;
  obs.origin_map = {origin.x(), origin.y(), 0.5};
  for (int i = 0; i < 1440; ++i) {
    const double a = 2.0 * M_PI * i / 1440.0;
    const Eigen::Vector2d d(std::cos(a), std::sin(a));
    double best = far_m;
    for (const auto& b : boxes)
      for (double t = 0.0; t < best; t += 0.005) {
        const Eigen::Vector2d p = origin + t * d;
        if (p.x() >= b.x0 && p.x() <= b.x1 && p.y() >= b.y0 && p.y() <= b.y1) {
          best = t;
          break;
        }
      }
    const Eigen::Vector2d p = origin + best * d;
    if (best < far_m) obs.points_map.emplace_back(float(p.x()), float(p.y()), 0.5f);
  }
  return obs;
}

int lethal_in(const Costmap2D& m, const Box& b) {
  int n = 0;
  for (int y = 0; y < m.height(); ++y)
    for (int x = 0; x < m.width(); ++x) {
      const auto c = m.geometry().cell_center(x, y);
      if (c.x() > b.x0 - 0.03 && c.x() < b.x1 + 0.03 && c.y() > b.y0 - 0.03 && c.y() < b.y1 + 0.03 &&
          m.cost(x, y) == kLethal)
        ++n;
    }
  return n;
}

}  // namespace

TEST(LocalCostmap, MovingBoxLeavesNoTrail) {
  LocalCostmap local;
  const Box wall{3.0, -4.0, 3.2, 4.0};
  const Box box_a{1.5, -0.3, 1.8, 0.3};
  const Box box_b{1.5, 1.2, 1.8, 1.8};
  local.update({0.0, 0.0, 0.0}, {scan({0, 0}, {wall, box_a})});
  EXPECT_GT(lethal_in(local.obstacles(), box_a), 5);
  EXPECT_GT(lethal_in(local.obstacles(), wall), 20);
  EXPECT_EQ(local.costmap().cost(*local.geometry().world_to_cell(1.52, 0.0)), kLethal);
  // The box moves: rays now pass through its old place to the wall.
  const ChangeSet changes = local.update({0.0, 0.0, 0.0}, {scan({0, 0}, {wall, box_b})});
  EXPECT_EQ(lethal_in(local.obstacles(), box_a), 0);
  EXPECT_GT(lethal_in(local.obstacles(), box_b), 5);
  EXPECT_GT(lethal_in(local.obstacles(), wall), 20);
  EXPECT_FALSE(changes.empty());
  // The inflated costmap around the old box is free again (apart from the wall's inflation).
  EXPECT_EQ(local.costmap().cost(*local.geometry().world_to_cell(1.6, 0.0)), kFree);
}

TEST(LocalCostmap, WindowFollowsRobotAndKeepsObstacles) {
  LocalCostmap local;
  EXPECT_EQ(local.geometry().width, 160);
  Observation obs;
  obs.origin_map = {0, 0, 0.5};
  obs.points_map = {{1.02f, 1.02f, 0.3f}};
  obs.clearing = false;
  local.update({0.0, 0.0, 0.0}, {obs});
  local.update({1.0, 0.5, 0.3}, {});
  const auto& g = local.geometry();
  EXPECT_NEAR(g.origin_x_m, 1.0 - 4.0, 1e-9);
  EXPECT_NEAR(g.origin_y_m, 0.5 - 4.0, 1e-9);
  EXPECT_EQ(local.obstacles().cost(*g.world_to_cell(1.02, 1.02)), kLethal);
  local.update({6.0, 0.0, 0.0}, {});  // the obstacle left the window
  EXPECT_EQ(std::count(local.obstacles().data().begin(), local.obstacles().data().end(), kLethal), 0);
  local.update({0.0, 0.0, 0.0}, {});  // and does not come back
  EXPECT_EQ(std::count(local.obstacles().data().begin(), local.obstacles().data().end(), kLethal), 0);
}

TEST(LocalCostmap, IgnoresNaNFarAndOutOfMapPoints) {
  LocalCostmap local;
  Observation obs;
  obs.origin_map = {0, 0, 0.5};
  const float nan = std::nanf("");
  obs.points_map = {{nan, 1.0f, 0.3f},   {1.0f, nan, 0.3f},   {1.0f, 1.0f, nan},
                    {20.0f, 0.0f, 0.3f}, {3.95f, 0.0f, 0.3f}, {1.0f, -1.0f, 0.3f}};
  obs.max_range_m = 10.0;
  local.update({0.0, 0.0, 0.0}, {obs});
  // 3.95 m is inside the window but beyond obstacle_max_range_m (4.0 m from z=0.5)? No: sqrt(3.95^2+0.2^2) < 4.
  const auto& o = local.obstacles().data();
  EXPECT_EQ(std::count(o.begin(), o.end(), kLethal), 2);
  EXPECT_EQ(local.obstacles().cost(*local.geometry().world_to_cell(1.0, -1.0)), kLethal);
  // The 20 m return cleared its ray up to the window's edge.
  EXPECT_EQ(local.observed().cost(*local.geometry().world_to_cell(3.0, 0.01)), kFree);
  EXPECT_EQ(local.observed().cost(*local.geometry().world_to_cell(-3.0, 0.01)), kUnknown);
  EXPECT_THROW(local.update({std::nan(""), 0.0, 0.0}, {}), bipednav::Error);
}

TEST(LocalCostmap, ChangeSetIsDiffAndClearForgets) {
  LocalCostmap local;
  Observation obs;
  obs.origin_map = {0, 0, 0.5};
  obs.points_map = {{1.0f, 0.0f, 0.3f}};
  local.update({0.0, 0.0, 0.0}, {});
  const Costmap2D before = local.costmap();
  const ChangeSet ch = local.update({0.0, 0.0, 0.0}, {obs});
  const ChangeSet expect = diff(before, local.costmap());
  ASSERT_EQ(ch.size(), expect.size());
  for (std::size_t i = 0; i < ch.size(); ++i) {
    EXPECT_EQ(ch[i].cell, expect[i].cell);
    EXPECT_EQ(ch[i].new_cost, expect[i].new_cost);
  }
  local.clear();
  EXPECT_EQ(std::count(local.costmap().data().begin(), local.costmap().data().end(), kFree), 160 * 160);
}

TEST(LocalCostmap, RejectsBadParams) {
  LocalCostmapParams p;
  p.resolution_m = 0.0;
  EXPECT_THROW(LocalCostmap{p}, bipednav::ParamError);
  p = {};
  p.inflation_radius_m = 0.1;  // below the inscribed radius
  EXPECT_THROW(LocalCostmap{p}, bipednav::ParamError);
  p = {};
  p.raytrace_max_range_m = -1;
  EXPECT_THROW(LocalCostmap{p}, bipednav::ParamError);
}

namespace {

// A 0.3 x 0.4 m obstacle seen by a depth camera at heights 0.1-0.5 m (a low cylinder or box).
Observation low_obstacle_seen() {
  Observation obs;
  obs.origin_map = {0, 0, 0.95};
  for (float y = -0.2f; y <= 0.2f; y += 0.02f)
    for (float z : {0.1f, 0.3f, 0.5f}) obs.points_map.emplace_back(1.0f, y, z);
  return obs;
}

// Rays from (0, 0, origin_z) to the points (x, x y, z), y in [-0.25, 0.25]: they cross all the
// obstacle's cells at x = 1.0-1.05 m.
Observation rays_beyond(double origin_z, float x, float z) {
  Observation obs;
  obs.origin_map = {0, 0, origin_z};
  obs.marking = false;
  for (float y = -0.25f; y <= 0.25f; y += 0.005f) obs.points_map.emplace_back(x, y * x, z);  // (1, y) on the way
  return obs;
}

int lethal_count(const LocalCostmap& m) {
  return static_cast<int>(std::count(m.obstacles().data().begin(), m.obstacles().data().end(), kLethal));
}

}  // namespace

LocalCostmapParams height_aware() {
  LocalCostmapParams p;
  p.height_aware_clearing = true;
  return p;
}

TEST(LocalCostmap, RaysPassingAboveALowObstacleKeepIt) {
  LocalCostmap plain;  // 2D clearing (the default): the LiDAR rays erase it
  plain.update({0.0, 0.0, 0.0}, {low_obstacle_seen()});
  EXPECT_GE(lethal_count(plain), 8);
  plain.update({0.0, 0.0, 0.0}, {rays_beyond(1.47, 2.5f, 0.9f)});
  EXPECT_EQ(lethal_count(plain), 0);

  LocalCostmap local(height_aware());
  local.update({0.0, 0.0, 0.0}, {low_obstacle_seen()});
  const int marked = lethal_count(local);
  EXPECT_GE(marked, 8);
  // LiDAR rays from 1.47 m to returns at 0.9 m, 2.5 m away: over the obstacle they are 1.24 m high.
  // (Rays to the floor 2.5 m away would pass at 0.57 m, above it, too.)
  local.update({0.0, 0.0, 0.0}, {rays_beyond(1.47, 2.5f, 0.9f)});
  EXPECT_EQ(lethal_count(local), marked);
  // The window moves (the bands move with it): still kept by the same rays, seen from the new place.
  local.update({0.5, 0.0, 0.0}, {});
  local.update({0.5, 0.0, 0.0}, {rays_beyond(1.47, 2.5f, 0.9f)});
  EXPECT_EQ(lethal_count(local), marked);
  // Rays to the floor 1.6 m away cross its cells at 0.33-0.36 m, inside 0.1-0.5 m: it is gone.
  local.update({0.5, 0.0, 0.0}, {rays_beyond(0.95, 1.6f, 0.0f)});
  EXPECT_EQ(lethal_count(local), 0);
}

TEST(LocalCostmap, AMovingObstacleKeepsNoHeights) {
  LocalCostmap local(height_aware());
  Observation person = low_obstacle_seen();
  person.keep_heights = false;  // the navigator's tracker says it moves
  local.update({0.0, 0.0, 0.0}, {person});
  EXPECT_GE(lethal_count(local), 8);
  local.update({0.0, 0.0, 0.0}, {rays_beyond(1.47, 2.5f, 0.9f)});
  EXPECT_EQ(lethal_count(local), 0);
}

TEST(LocalCostmap, GlobalMapKeepsTheHeightsOfMergedObstacles) {
  LocalCostmap local(height_aware());
  local.update({0.0, 0.0, 0.0}, {low_obstacle_seen()});
  GlobalCostmapParams gp;
  gp.height_aware_clearing = true;
  GlobalCostmap global({100, 100, 0.1, -5.0, -5.0}, gp);
  global.update({0, 0, 0}, {}, &local);
  const auto lethal = [&] {
    return std::count(global.occupancy().data().begin(), global.occupancy().data().end(), kLethal);
  };
  const auto merged = lethal();
  EXPECT_GE(merged, 4);
  // The robot walks away (no local window over the obstacle); the LiDAR rays pass over it.
  global.update({-3.0, 0.0, 0.0}, {rays_beyond(1.47, 2.5f, 0.9f)}, nullptr);
  EXPECT_EQ(lethal(), merged);
  global.update({-3.0, 0.0, 0.0}, {rays_beyond(0.95, 1.6f, 0.0f)}, nullptr);
  EXPECT_EQ(lethal(), 0);
}
