#pragma once

#include <filesystem>
#include <string>

#include "bipednav/io/param_reader.hpp"
#include "bipednav/navigation/navigator.hpp"

namespace bipednav::navigation {

// A navigation parameters file (like a Nav2 params.yaml): a YAML mapping that mirrors
// NavigatorParams with the structs' own field names, nested structs as nested mappings, e.g.
//
//   control_rate_hz: 10.0
//   local_map: {inflation_radius_m: 0.6}
//   server:
//     local_planner: teb
//     local: {teb: {optim: {dynamic_obstacles: true}}}
//
// Every key is optional: the file is overlaid on parameters that already hold the robot's
// defaults (NavigatorParams::for_robot). `bipednav params --robot R` prints the full layout.
// Left out (not tunable from a file): localization.loam.T_world_lidar_initial and
// output_deskewed (the Localizer sets them), perception.ransac.prior_normal (taken from
// perception.prior_ground) and server.local.moving_obstacles (the navigator's tracker).

// Overlays the mapping `r` onto `p`, then p.validate(). An unknown key or a value of the wrong type
// raises FileError naming the file and the field's path (e.g. server.local.teb.optim.foo); a value
// out of range raises FileError naming the file with validate()'s message (the field's name).
void read_navigator_params(io::ParamReader& r, NavigatorParams& p);
// read_navigator_params on the YAML file `file`.
void apply_navigator_params_file(const std::filesystem::path& file, NavigatorParams& p);
// `p` as YAML in the layout read_navigator_params reads, every field it reads included (reading the
// text back gives the same values).
std::string navigator_params_yaml(const NavigatorParams& p);

}  // namespace bipednav::navigation
