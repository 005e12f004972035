// Per-robot navigator defaults.
#include <gtest/gtest.h>

#include "bipednav/mapping/obstacle_layer.hpp"
#include "bipednav/navigation/navigator.hpp"

using namespace bipednav;

TEST(NavigatorParams, WheeledRobotsProjectLoamsReferenceWithThePriorChange) {
  RobotProfile robot;
  for (const char* kind : {"diff_drive", "walker", "humanoid"}) {
    robot.kind = kind;
    const auto p = navigation::NavigatorParams::for_robot(robot);
    const bool wheeled = robot.kind == "diff_drive";
    EXPECT_EQ(p.localization.loam.reference_from_prior_change, wheeled) << kind;
    EXPECT_EQ(mapping::height_aware_maps_for(robot), wheeled) << kind;
  }
}
