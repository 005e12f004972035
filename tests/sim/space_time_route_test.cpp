#include "bipednav/sim/space_time_route.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/world_parts.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::sim;

constexpr double kRadius = 0.2, kSpeed = 0.5;  // dt = 2 * 0.05 / 0.5 = 0.2 s: 0.1 m per step
const RouteArea kArea{{0, -1}, {6, 1}};

// A corridor along x from 0 to 4, its walls' inner faces at y = +-0.55 (a robot of radius 0.2
// keeps |y| <= 0.35), open at x = 4 onto the rest of the area.
World corridor() {
  World w;
  w.statics.push_back(wall_segment("south", {0, -0.6}, {4, -0.6}));
  w.statics.push_back(wall_segment("north", {0, 0.6}, {4, 0.6}));
  w.statics.push_back(wall_segment("west", {0, -0.6}, {0, 0.6}));
  return w;
}

// A person of radius 0.25 standing at (3, 0) in the corridor until `leaves_s`, then walking out
// along +x at 1 m/s to (5.5, 0), where it stays (never, with leaves_s infinite).
Actor blocking_person(double leaves_s) {
  Actor a = person("person", 0.25, {{3, 0}, {5.5, 0}}, 1.0, 0.0);
  SE3 at = a.trajectory.front().pose;
  at.translation().head<2>() = Eigen::Vector2d(3, 0);
  a.trajectory = {{0.0, at}};
  if (std::isfinite(leaves_s)) {
    SE3 out = at;
    out.translation().x() = 5.5;
    a.trajectory.push_back({leaves_s, at});
    a.trajectory.push_back({leaves_s + 2.5, out});
  }
  a.loop = false;
  return a;
}

TEST(SpaceTimeRoute, WithoutPeopleTheRobotDrivesStraightAtTopSpeed) {
  const SpaceTimeRoute r = space_time_route(corridor(), kArea, {0.5, 0}, {3.5, 0}, 0.0, kRadius, kSpeed, 60.0);
  ASSERT_TRUE(r.reachable);
  EXPECT_NEAR(r.step_s, 0.2, 1e-12);
  // 3 m at 0.1 m per step: 30 steps.
  EXPECT_NEAR(r.static_arrival_s, 6.0, 1e-9);
  EXPECT_NEAR(r.arrival_s, 6.0, 1e-9);
}

TEST(SpaceTimeRoute, WaitsBehindAPersonUntilItLeavesTheCorridor) {
  World w = corridor();
  w.actors.push_back(blocking_person(8.0));
  const SpaceTimeRoute r = space_time_route(w, kArea, {0.5, 0}, {3.5, 0}, 0.0, kRadius, kSpeed, 60.0);
  ASSERT_TRUE(r.reachable);
  EXPECT_NEAR(r.static_arrival_s, 6.0, 1e-9);
  // The robot keeps 0.45 m from the person's centre: it waits beside the wall 0.28-0.45 m short of
  // the person until the person walks off at 8 s (faster than the robot), then drives the last
  // 0.8-0.95 m at 0.5 m/s: 9.6-9.9 s.
  EXPECT_GE(r.arrival_s, 9.4);
  EXPECT_LE(r.arrival_s, 10.4);
}

TEST(SpaceTimeRoute, APersonWhoNeverLeavesClosesTheCorridor) {
  World w = corridor();
  w.actors.push_back(blocking_person(std::numeric_limits<double>::infinity()));
  const SpaceTimeRoute r = space_time_route(w, kArea, {0.5, 0}, {3.5, 0}, 0.0, kRadius, kSpeed, 60.0);
  EXPECT_FALSE(r.reachable);
  EXPECT_TRUE(std::isinf(r.arrival_s));
  EXPECT_NEAR(r.static_arrival_s, 6.0, 1e-9);  // the static world alone is open
}

TEST(SpaceTimeRoute, TheTimeLimitCounts) {
  World w = corridor();
  w.actors.push_back(blocking_person(8.0));
  EXPECT_FALSE(space_time_route(w, kArea, {0.5, 0}, {3.5, 0}, 0.0, kRadius, kSpeed, 9.0).reachable);
}

TEST(SpaceTimeRoute, APersonWalkingIntoAWaitingRobotIsAContact) {
  // The person walks back along the corridor towards the start, which leaves the robot nowhere
  // to stand: the corridor is a dead end and the person reaches its west wall.
  World w = corridor();
  Actor a = person("person", 0.25, {{3.5, 0}, {0.3, 0}}, 0.5, 0.0);
  a.loop = false;
  a.trajectory.resize(2);  // 3.5 -> 0.3, then stays
  w.actors.push_back(a);
  EXPECT_FALSE(space_time_route(w, kArea, {1.0, 0}, {3.5, 0}, 0.0, kRadius, kSpeed, 60.0).reachable);
}

TEST(SpaceTimeRoute, RejectsBadInput) {
  const World w = corridor();
  EXPECT_THROW(space_time_route(w, kArea, {0.5, 0}, {3.5, 0}, 0.0, 0.0, kSpeed, 60.0), ParamError);
  EXPECT_THROW(space_time_route(w, kArea, {0.5, 0}, {3.5, 0}, 0.0, kRadius, -1.0, 60.0), ParamError);
  EXPECT_THROW(space_time_route(w, kArea, {0.5, 0}, {3.5, 0}, 0.0, kRadius, kSpeed, 0.0), ParamError);
  EXPECT_THROW(space_time_route(w, kArea, {NAN, 0}, {3.5, 0}, 0.0, kRadius, kSpeed, 60.0), ParamError);
  EXPECT_THROW(space_time_route(w, RouteArea{{1, 1}, {0, 0}}, {0.5, 0}, {3.5, 0}, 0.0, kRadius, kSpeed, 60.0),
               ParamError);
  SpaceTimeRouteParams p;
  p.resolution_m = 0.0;
  EXPECT_THROW(space_time_route(w, kArea, {0.5, 0}, {3.5, 0}, 0.0, kRadius, kSpeed, 60.0, p), ParamError);
}

TEST(SpaceTimeRoute, AStartInsideAnObstacleIsNotReachable) {
  const SpaceTimeRoute r = space_time_route(corridor(), kArea, {0.5, 0.55}, {3.5, 0}, 0.0, kRadius, kSpeed, 60.0);
  EXPECT_FALSE(r.reachable);
  EXPECT_TRUE(std::isinf(r.static_arrival_s));
}

}  // namespace
