// Per-robot navigator defaults.
#include <gtest/gtest.h>

#include <utility>

#include "bipednav/navigation/navigator.hpp"
#include "bipednav/navigation/robot_loading.hpp"

using namespace bipednav;

// The robots' tuning is data: config/<name>.params.yaml on top of the values derived from the profile.
TEST(NavigatorParams, EachRobotsTuningComesFromItsParamsFile) {
  const auto tb3 = navigation::navigator_params_for(navigation::load_robot("turtlebot3"));
  EXPECT_TRUE(tb3.localization.loam.reference_from_prior_change);
  for (const auto* m : {&tb3.local_map.height_aware_clearing, &tb3.global_map.height_aware_clearing}) EXPECT_TRUE(*m);
  EXPECT_EQ(tb3.local_map.obstacle_layer().mark_lifetime_updates, mapping::decay_updates(5.0, 10.0));
  EXPECT_EQ(tb3.global_map.obstacle_layer().mark_lifetime_updates, mapping::decay_updates(5.0, 2.0));
  EXPECT_EQ(tb3.server.local_planner, "teb");
  const auto digit = navigation::navigator_params_for(navigation::load_robot("digit"));
  EXPECT_FALSE(digit.localization.loam.reference_from_prior_change);
  EXPECT_FALSE(digit.local_map.height_aware_clearing);
  EXPECT_EQ(digit.server.local_planner, "tracker");
  EXPECT_TRUE(digit.brake_from_last_command);
  // A profile of one's own without a params file: the structs' defaults and the derived values.
  RobotProfile own = navigation::load_robot("digit");
  own.name = "my_walker";
  EXPECT_TRUE(navigation::robot_params_file(own).empty());
  const auto mine = navigation::navigator_params_for(own);
  EXPECT_EQ(mine.server.local_planner, navigation::ServerParams{}.local_planner);
  EXPECT_FALSE(mine.brake_from_last_command);
  EXPECT_EQ(mine.server.local.tracker.limits.max_vel_x_mps, own.limits.max_vel_x_mps);
  EXPECT_EQ(mine.local_map.inscribed_radius_m, digit.local_map.inscribed_radius_m);
}

// TEB's body response model is the profile's velocity lag, whatever the kind, where the lag spans at
// least a control period (0.1 s at 10 Hz).
TEST(NavigatorParams, TebModelsTheProfilesVelocityLag) {
  RobotProfile robot;
  for (const char* kind : {"diff_drive", "walker"}) {
    robot.kind = kind;
    for (const auto& [tau_s, modelled_s] : {std::pair{0.0, 0.0}, {0.05, 0.0}, {0.1, 0.1}, {0.3, 0.3}}) {
      robot.tracking_time_constant_s = tau_s;
      const auto p = navigation::NavigatorParams::for_robot(robot);
      EXPECT_EQ(p.server.local.teb.response.time_constant_s, modelled_s) << kind << " " << tau_s;
    }
  }
}

TEST(NavigatorParams, LocalPlannersAimAtAShareOfTheGoalCheckersTolerance) {
  navigation::ServerParams p;
  p.goal.xy_tolerance_m = 0.2;
  p.goal.yaw_tolerance_rad = 0.3;
  p.controller_goal_tolerance_fraction = 0.5;
  navigation::apply_controller_goal_tolerances(p);
  for (const double xy : {p.local.teb.xy_goal_tolerance_m, p.local.tracker.xy_goal_tolerance_m})
    EXPECT_DOUBLE_EQ(xy, 0.1);
  for (const double yaw : {p.local.teb.yaw_goal_tolerance_rad, p.local.tracker.yaw_goal_tolerance_rad})
    EXPECT_DOUBLE_EQ(yaw, 0.15);
  for (const double release : {p.local.teb.xy_goal_release_m, p.local.tracker.xy_goal_release_m})
    EXPECT_DOUBLE_EQ(release, 0.2);
  navigation::ServerParams own;
  own.controller_goal_tolerance_fraction = 0.0;  // the planners keep their own tolerances
  own.local.teb.xy_goal_tolerance_m = 0.3;
  navigation::apply_controller_goal_tolerances(own);
  EXPECT_DOUBLE_EQ(own.local.teb.xy_goal_tolerance_m, 0.3);
  EXPECT_DOUBLE_EQ(own.local.tracker.xy_goal_release_m, 0.0);
  own.controller_goal_tolerance_fraction = 1.5;
  EXPECT_THROW(own.validate(), ParamError);
}

// The local planner yields to the navigator's own tracker (held by value; the planner keeps a pointer).
TEST(NavigatorParams, TheLocalPlannerReadsTheNavigatorsMovingObstacleTracker) {
  for (const char* kind : {"diff_drive", "walker"}) {
    RobotProfile robot;
    robot.kind = kind;
    const navigation::Navigator nav(navigation::NavigatorParams::for_robot(robot), robot,
                                    mapping::GridGeometry{100, 100, 0.1, -5.0, -5.0}, {});
    EXPECT_EQ(nav.server().local_planner().moving_obstacles(), &nav.moving_obstacles()) << kind;
  }
}

// Bad parameters are reported by name before any stage is built from them (an empty tree path
// must not reach the XML loader and come back as an unreadable file).
TEST(NavigatorParams, TheNavigatorNamesABadParameterBeforeBuildingItsStages) {
  RobotProfile robot;
  navigation::NavigatorParams p = navigation::NavigatorParams::for_robot(robot);
  p.behavior_tree.clear();
  const mapping::GridGeometry grid{100, 100, 0.1, -5.0, -5.0};
  try {
    navigation::Navigator nav(p, robot, grid, {});
    FAIL() << "an empty behavior_tree must be rejected";
  } catch (const ParamError& e) {
    EXPECT_NE(std::string(e.what()).find("behavior_tree"), std::string::npos) << e.what();
  }
  robot.limits.max_vel_x_mps = -1.0;
  EXPECT_THROW(navigation::Navigator(navigation::NavigatorParams::for_robot(RobotProfile{}), robot, grid, {}),
               ParamError);
}
