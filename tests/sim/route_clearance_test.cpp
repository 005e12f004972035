#include "bipednav/sim/route_clearance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "bipednav/common/error.hpp"
#include "test_data.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::sim;

// A wall along x = 0 (0.2 m thick, 1 m tall) from y = -3 to 3 with a door from y = -0.3 to 0.3.
World door_world(double half_gap_m) {
  World w;
  w.statics.push_back({"ground", SE3::Identity(), Plane{}});  // not an obstacle
  const double len = 3.0 - half_gap_m;
  w.statics.push_back({"upper", make_se3(0, half_gap_m + len / 2, 0.5, 0, 0, 0), Box{{0.2, len, 1.0}}});
  w.statics.push_back({"lower", make_se3(0, -half_gap_m - len / 2, 0.5, 0, 0, 0), Box{{0.2, len, 1.0}}});
  return w;
}

const RouteArea kArea{{-2, -2}, {2, 2}};

TEST(WidestRoute, ThroughADoorIsHalfTheDoorsWidth) {
  const RouteClearance r = widest_route(door_world(0.3), kArea, {-1.5, 0.4}, {1.5, -0.7});
  ASSERT_TRUE(r.connected);
  // The door's centre line (y = 0) is a row of grid cells: the route keeps exactly 0.3 m there.
  EXPECT_NEAR(r.widest_m, 0.3, 1e-6);  // tessellated corners: single precision
  // The narrowest point of the route found is in the door (cells level with the door posts' corners
  // keep 0.3 m too).
  EXPECT_LT(std::abs(r.bottleneck.x()), 0.4);
  EXPECT_LT(std::abs(r.bottleneck.y()), 0.3);
  EXPECT_TRUE(r.bottleneck_obstacle == "upper" || r.bottleneck_obstacle == "lower") << r.bottleneck_obstacle;
  EXPECT_GT(r.cells_searched, 0u);
}

TEST(WidestRoute, AClosedWallHasNoRoute) {
  const RouteClearance r = widest_route(door_world(0.0), kArea, {-1.5, 0.0}, {1.5, 0.0});
  EXPECT_FALSE(r.connected);
  EXPECT_EQ(r.widest_m, 0.0);
}

TEST(WidestRoute, ObstaclesAboveTheRobotDoNotCount) {
  World w = door_world(0.0);
  // A robot 0.4 m tall passes under the wall raised to z in [0.5, 1.5].
  for (auto& g : w.statics) g.T_parent_shape.translation().z() += 1.0;
  RouteClearanceParams low;
  low.height_m = 0.4;
  EXPECT_TRUE(widest_route(w, kArea, {-1.5, 0.0}, {1.5, 0.0}, low).connected);
  EXPECT_FALSE(widest_route(w, kArea, {-1.5, 0.0}, {1.5, 0.0}).connected);  // 1 m tall
}

TEST(WidestRoute, StartInsideAnObstacleOrOutsideTheAreaHasNoRoute) {
  const World w = door_world(0.3);
  EXPECT_FALSE(widest_route(w, kArea, {0.0, 1.0}, {1.5, 0.0}).connected);  // inside the wall
  EXPECT_FALSE(widest_route(w, kArea, {-2.5, 0.0}, {1.5, 0.0}).connected);
  EXPECT_FALSE(widest_route(w, kArea, {std::nan(""), 0.0}, {1.5, 0.0}).connected);
}

TEST(WidestRoute, WithoutObstaclesTheRouteIsUnbounded) {
  const RouteClearance r = widest_route(World{}, kArea, {-1.0, 0.0}, {1.0, 0.0});
  EXPECT_TRUE(r.connected);
  EXPECT_TRUE(std::isinf(r.widest_m));
}

TEST(WidestRoute, RejectsBadParameters) {
  RouteClearanceParams p;
  p.resolution_m = 0.0;
  EXPECT_THROW(widest_route(World{}, kArea, {0, 0}, {1, 1}, p), ParamError);
  EXPECT_THROW(widest_route(World{}, RouteArea{{1, 1}, {0, 2}}, {0, 0}, {1, 1}), ParamError);
  // 4e14 cells of 1 cm: refused before anything is allocated.
  EXPECT_THROW(widest_route(World{}, RouteArea{{-1e5, -1e5}, {1e5, 1e5}}, {0, 0}, {1, 1}), ParamError);
}

// The scenarios (Digit's slab, 1.6 m): the goal of hexagon_dynamic and turtlebot3_world,
// and hexagon_static's first goal, lie behind a 0.8 m gap between cylinders (0.4 m from its centre
// line, where Digit needs 0.35 m footprint + 0.03 m sway); the other goals have far more room.
TEST(WidestRoute, RoomToTheScenariosGoals) {
  RouteClearanceParams digit;
  digit.height_m = 1.6;
  const auto routes = [&](const std::string& name) {
    return scenario_routes(load_scenario(test::source_dir() / "scenarios" / (name + ".yaml")), digit);
  };
  const auto hexagon = routes("hexagon_static");
  ASSERT_EQ(hexagon.size(), 2u);
  EXPECT_NEAR(hexagon[0].widest_m, 0.40, 0.005);
  EXPECT_NEAR(hexagon[1].widest_m, 0.55, 0.005);
  EXPECT_NEAR(routes("hexagon_dynamic").at(0).widest_m, 0.40, 0.005);
  EXPECT_NEAR(routes("turtlebot3_world").at(0).widest_m, 0.40, 0.005);
  EXPECT_GT(routes("three_rooms").at(0).widest_m, 0.6);
}

}  // namespace

TEST(WidestRoute, PathGoesThroughTheDoorKeepingTheWidestRoom) {
  RouteClearanceParams p;
  p.resolution_m = 0.02;
  EXPECT_TRUE(widest_route(door_world(0.3), kArea, {-1.5, 0.4}, {1.5, -0.7}, p).path.empty());  // not asked for
  p.with_path = true;
  const RouteClearance r = widest_route(door_world(0.3), kArea, {-1.5, 0.4}, {1.5, -0.7}, p);
  ASSERT_TRUE(r.connected);
  ASSERT_GE(r.path.size(), 2u);
  EXPECT_LT((r.path.front() - Eigen::Vector2d(-1.5, 0.4)).norm(), p.resolution_m);
  EXPECT_LT((r.path.back() - Eigen::Vector2d(1.5, -0.7)).norm(), p.resolution_m);
  bool through_door = false;
  for (std::size_t i = 0; i < r.path.size(); ++i) {
    if (i > 0) {
      EXPECT_LE((r.path[i] - r.path[i - 1]).norm(), p.resolution_m * std::sqrt(2.0) + 1e-9);
    }
    // Within the wall's thickness: in the door's middle row, the only one keeping 0.3 m.
    if (std::abs(r.path[i].x()) <= 0.1 + 1e-6) {
      EXPECT_NEAR(r.path[i].y(), 0.0, 1e-6) << i;
      through_door = true;
    }
  }
  EXPECT_TRUE(through_door);
}

TEST(RouteWaypoints, ThinsAPathKeepingItsEnd) {
  std::vector<Eigen::Vector2d> path;
  for (int i = 0; i <= 100; ++i) path.emplace_back(0.05 * i, 0.0);  // 5 m
  const auto w = route_waypoints(path, 0.75);
  ASSERT_FALSE(w.empty());
  EXPECT_EQ(w.back(), path.back());
  for (std::size_t i = 1; i < w.size(); ++i) {
    EXPECT_GE(w[i].x() - w[i - 1].x(), i + 1 == w.size() ? 0.0 : 0.75 - 1e-9);
    EXPECT_LE(w[i].x() - w[i - 1].x(), 0.8 + 1e-9);
  }
  EXPECT_GE(w.front().x(), 0.75 - 1e-9);
  EXPECT_LE(w.front().x(), 0.8 + 1e-9);
  EXPECT_EQ(route_waypoints({{1.0, 2.0}}, 0.75), std::vector<Eigen::Vector2d>{Eigen::Vector2d(1.0, 2.0)});
  EXPECT_TRUE(route_waypoints({}, 0.75).empty());
  EXPECT_THROW(route_waypoints(path, 0.0), ParamError);
}
