#include "ros/map_params.hpp"

#include <gtest/gtest.h>

#include "bipednav/common/error.hpp"

namespace bipednav::ros1 {
namespace {

// The simulator node's dictionary gives the navigation node its scenario's area and start.
TEST(RosMapParams, TheDictionaryRoundTripsEveryField) {
  MapParams sim;
  sim.area = {-3.5, -2.0, 4.0, 3.25, 2.0};
  sim.initial = {-1.0, 0.5, 1.25};
  const std::map<std::string, double> d = to_param(sim);
  ASSERT_EQ(d.size(), 8u);
  EXPECT_EQ(d.at("map_min_x_m"), -3.5);
  EXPECT_EQ(d.at("map_margin_m"), 2.0);
  EXPECT_EQ(d.at("initial_theta_rad"), 1.25);
  MapParams nav;
  apply_param(d, "/bipednav_sim/map_area", nav);
  EXPECT_EQ(nav.area.min_x_m, -3.5);
  EXPECT_EQ(nav.area.min_y_m, -2.0);
  EXPECT_EQ(nav.area.max_x_m, 4.0);
  EXPECT_EQ(nav.area.max_y_m, 3.25);
  EXPECT_EQ(nav.area.margin_m, 2.0);
  EXPECT_EQ(nav.initial.x, -1.0);
  EXPECT_EQ(nav.initial.y, 0.5);
  EXPECT_EQ(nav.initial.theta, 1.25);
}

TEST(RosMapParams, AbsentKeysKeepTheirValuesAndAnUnknownKeyIsNamed) {
  MapParams p;
  apply_param({{"map_max_x_m", 30.0}}, "area", p);
  EXPECT_EQ(p.area.max_x_m, 30.0);
  EXPECT_EQ(p.area.min_x_m, -10.0);  // MapArea's default
  EXPECT_EQ(p.initial.x, 0.0);
  try {
    apply_param({{"map_min_x_m", 1.0}, {"map_max_x", 5.0}}, "/bipednav_sim/map_area", p);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("/bipednav_sim/map_area: unknown key 'map_max_x'"), std::string::npos) << m;
    EXPECT_NE(m.find("map_max_x_m"), std::string::npos) << m;  // the keys it takes
  }
  EXPECT_EQ(p.area.min_x_m, -10.0);  // nothing set from a rejected dictionary
}

}  // namespace
}  // namespace bipednav::ros1
