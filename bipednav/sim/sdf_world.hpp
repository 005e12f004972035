#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

// Reads a Gazebo world (or a single-model SDF file) through libsdformat 12 into a World.
//
// - Every model (static or not, nested, or <include>d) contributes its links' collision
//   geometry, posed by composing model, nested-model, link and collision poses; a link without
//   <collision> falls back to its <visual> geometry. Non-static models are frozen at their
//   initial pose (there is no physics here).
// - `model://name/...` URIs (includes and meshes) resolve through `model_paths`, then through
//   `<world dir>/models` and `<world dir>/../models` when they exist (the Gazebo layout).
// - Includes from Gazebo Fuel (http/https) cannot be fetched offline: "Ground Plane" becomes an
//   unbounded z = 0 plane, anything else (the sun, ...) is skipped.
// - Capsules become cylinders of length + 2 r and ellipsoids boxes of 2 x radii (conservative);
//   heightmaps are rejected.
// - <actor>: its links' geometry in the actor frame; <script><trajectory> waypoints (several
//   trajectories are played one after another), <loop> and <delay_start>. An actor with only a
//   skin/animation gets a stand-in cylinder of radius 0.3 m and height 1.8 m standing on z = 0
//   (at the height of its first waypoint).
//
// Errors from sdformat (and unreadable meshes) raise FileError naming the file and the message.
World load_sdf_world(const std::filesystem::path& file, const std::vector<std::filesystem::path>& model_paths = {});

// Resolves a mesh or include URI: `model://name/rest` through the model paths, `file://abs`,
// absolute paths, and paths relative to `base_dir`. Returns an empty path when nothing exists.
std::filesystem::path resolve_model_uri(const std::string& uri, const std::filesystem::path& base_dir,
                                        const std::vector<std::filesystem::path>& model_paths);

// Stand-in body of an actor without collision geometry (see above).
inline constexpr double kActorStandInRadius_m = 0.3;
inline constexpr double kActorStandInHeight_m = 1.8;

}  // namespace bipednav::sim
