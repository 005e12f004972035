#pragma once

// The navigation node's map parameters: the area its global map covers and the robot's initial
// pose in the map frame. A robot's launch file sets them one by one (~map_min_x_m, ...); the
// simulator node publishes its scenario's as one dictionary parameter (~map_area), which the
// navigation node reads when its ~map_area_param names it. So the navigation node sizes its map
// without a scenario file and without simulator code.

#include <map>
#include <string>

#include "bipednav/common/pose2.hpp"
#include "bipednav/navigation/map_area.hpp"

namespace bipednav::ros1 {

struct MapParams {
  navigation::MapArea area;
  Pose2 initial;  // the robot's pose in the map frame at start: the first map -> odom

  // Calls f(name, field) for each parameter: map_min_x_m, map_min_y_m, map_max_x_m, map_max_y_m,
  // map_margin_m, initial_x_m, initial_y_m, initial_theta_rad.
  template <typename F>
  void fields(F&& f) {
    f("map_min_x_m", area.min_x_m);
    f("map_min_y_m", area.min_y_m);
    f("map_max_x_m", area.max_x_m);
    f("map_max_y_m", area.max_y_m);
    f("map_margin_m", area.margin_m);
    f("initial_x_m", initial.x);
    f("initial_y_m", initial.y);
    f("initial_theta_rad", initial.theta);
  }
};

// The parameters as one dictionary (a ROS dictionary parameter of doubles).
std::map<std::string, double> to_param(MapParams p);
// Sets the fields the dictionary names; a key that names no field is an Error naming `param_name`
// and the key.
void apply_param(const std::map<std::string, double>& values, const std::string& param_name, MapParams& p);

}  // namespace bipednav::ros1
