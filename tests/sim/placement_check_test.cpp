#include "bipednav/sim/placement_check.hpp"

#include <gtest/gtest.h>

#include "bipednav/common/error.hpp"

using namespace bipednav;
using namespace bipednav::sim;

namespace {

// A 10 x 10 m room with one 1 x 1 m box "crate" centred at (5, 5), 1 m tall; a robot of radius 0.2 m.
Scenario crate_room() {
  Scenario s;
  s.name = "crate_room";
  s.world.statics.push_back({"crate", make_se3(5, 5, 0.5, 0, 0, 0), Box{Eigen::Vector3d(1, 1, 1)}});
  s.start = {1, 1, 0};
  s.goals = {{0.0, {8, 8, 0}}};
  s.bounds = {0, 0, 10, 10};
  s.goal_tolerance_m = 0.1;
  return s;
}

RobotProfile small_robot() {
  RobotProfile r;
  r.name = "small";
  r.footprint_radius_m = 0.2;
  r.height_m = 0.5;
  return r;
}

}  // namespace

TEST(PlacementCheck, FreePlacesPass) {
  const Scenario s = crate_room();
  EXPECT_FALSE(placement_problem(s, small_robot(), {8, 8, 0}, "the goal"));
  // 0.25 m from the crate's face: the footprint (0.2 m) fits.
  EXPECT_FALSE(placement_problem(s, small_robot(), {5.75, 5, 0}, "the goal"));
  EXPECT_NO_THROW(check_placements(s, small_robot()));
}

TEST(PlacementCheck, GoalInsideAnObstacleIsNamed) {
  const auto p = placement_problem(crate_room(), small_robot(), {5.2, 4.9, 0}, "the goal");
  ASSERT_TRUE(p);
  EXPECT_EQ(*p, "the goal (5.20, 4.90) is inside 'crate'");
}

TEST(PlacementCheck, FootprintOverlapBeyondTheToleranceIsReportedInMetres) {
  const Scenario s = crate_room();
  // 0.05 m from the face: the footprint overlaps the crate by 0.15 m, more than a 0.1 m tolerance ...
  const auto p = placement_problem(s, small_robot(), {5.55, 5, 0}, "the goal", {0.1, true});
  ASSERT_TRUE(p);
  EXPECT_NE(p->find("is 0.05 m from 'crate' (nearest point (5.50, 5.00))"), std::string::npos) << *p;
  EXPECT_NE(p->find("needs 0.20 m, less the tolerance 0.10 m"), std::string::npos) << *p;
  // ... but not more than a 0.2 m one: the robot can stop within the tolerance.
  EXPECT_FALSE(placement_problem(s, small_robot(), {5.55, 5, 0}, "the goal", {0.2, true}));
  // Without the obstacle check (a humanoid steps onto things) only the bounds count.
  EXPECT_FALSE(placement_problem(s, small_robot(), {5.2, 4.9, 0}, "the goal", {0.0, false}));
}

TEST(PlacementCheck, OffTheMap) {
  const auto p = placement_problem(crate_room(), small_robot(), {12, 5, 0}, "goal 2");
  ASSERT_TRUE(p);
  EXPECT_EQ(*p, "goal 2 (12.00, 5.00) is off the map (x 0.00 to 10.00 m, y 0.00 to 10.00 m)");
}

TEST(PlacementCheck, CheckPlacementsListsEveryProblem) {
  Scenario s = crate_room();
  s.start = {5, 5, 0};
  s.goals = {{0.0, {8, 8, 0}}, {10.0, {-1, 5, 0}}};
  try {
    check_placements(s, small_robot());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "crate_room with small: the start (5.00, 5.00) is inside 'crate'; goal 2 (-1.00, 5.00) is off the "
                 "map (x 0.00 to 10.00 m, y 0.00 to 10.00 m)");
  }
}
