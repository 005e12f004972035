#pragma once

#include <filesystem>
#include <string>

#include "bipednav/io/param_reader.hpp"
#include "bipednav/navigation/footstep_navigator.hpp"
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
// defaults (navigator_params_for: the derived values and config/<name>.params.yaml). `bipednav params --robot R` prints
// the full layout. Left out (not tunable from a file): localization.loam.T_world_lidar_initial and output_deskewed (the
// Localizer sets them) and perception.ransac.prior_normal (taken from perception.prior_ground).
//
// The footstep navigator of the humanoids (FootstepNavigatorParams, `bipednav run` with a robot of
// kind humanoid) reads a file of its own layout the same way, e.g.
//
//   replan_deviation_m: 0.03
//   planner: {search: {initial_epsilon: 3.0}}
//   odometry: {gicp: {max_correspondence_m: 0.1}}
//
// Top level: the navigator's scalars (gicp_correction, gicp_voxel_m, replan_deviation_m,
// replan_deviation_rad, obstacle_margin_m, obstacle_step_m, max_plans, max_recovery_steps), then
// planner (ARA* footsteps, with search), fusion (the Kalman heightmap) and odometry (GICP-corrected
// odometry, with gicp). Left out: planner.search.clock (wall or thread CPU time: it only measures
// search.time_limit_s and the reported times, and the closed loop plans without a time limit so
// that a run is reproducible). The whole-body collision model is not a parameter: it comes with
// the action set that planner.robot names (nao or digit). The footstep runner's own options
// (walker, camera, head yaws, map resolution: runner::FootstepRunOptions) are not the navigator's.

// Overlays the mapping `r` onto `p`, then p.validate(). An unknown key or a value of the wrong type
// raises FileError naming the file and the field's path (e.g. server.local.teb.optim.foo); a value
// out of range raises FileError naming the file with validate()'s message (the field's name).
void read_navigator_params(io::ParamReader& r, NavigatorParams& p);
void read_navigator_params(io::ParamReader& r, FootstepNavigatorParams& p);
// read_navigator_params on the YAML file `file`.
void apply_navigator_params_file(const std::filesystem::path& file, NavigatorParams& p);
void apply_navigator_params_file(const std::filesystem::path& file, FootstepNavigatorParams& p);
// `p` as YAML in the layout read_navigator_params reads, every field it reads included (reading the
// text back gives the same values).
std::string navigator_params_yaml(const NavigatorParams& p);
std::string navigator_params_yaml(const FootstepNavigatorParams& p);

}  // namespace bipednav::navigation
