#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "bipednav/mapping/global_costmap.hpp"

namespace bipednav::app {

// The inflation options of the commands that inflate a map_server map as the global costmap
// does (`costmap inflate`, `plan grid`): one set of names, checked the same way.
struct InflationFlags {
  double inscribed_radius_m = 0.2, inflation_radius_m = 0.55, cost_scaling = 3.0;
  std::string unknown = "unknown";

  // --inscribed-radius, --inflation-radius, --cost-scaling, --unknown.
  void add_to(CLI::App* command);
  // The global costmap's parameters for a map of this resolution; throws Error naming the option
  // at fault (e.g. an inflation radius below the inscribed one).
  mapping::GlobalCostmapParams params(double resolution_m) const;
};

}  // namespace bipednav::app
