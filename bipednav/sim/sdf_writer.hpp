#pragma once

#include <filesystem>
#include <string>

#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

// Writes a World as a Gazebo world file (SDF 1.7) that load_sdf_world reads back to the same
// geometry and actor scripts, and that Gazebo opens:
// - static geometry: one static model per name prefix (the part of a geometry's name before the
//   first "::"), each geometry a collision and a visual of its one link "link", posed in the world;
//   read back, a geometry named "table_1::top" is "table_1::link::top" and "wall_2" is
//   "wall_2::link::wall_2";
// - actors: their parts as collisions and visuals of a link "body", and their trajectory as one
//   <script><trajectory>, with <loop> and <delay_start>;
// - a ground plane model "ground_plane" unless the world has a horizontal plane.
// Boxes, cylinders, spheres and planes only: a mesh raises Error (its file is not kept).
std::string sdf_world_xml(const World& world);
// The same into a file (its directory must exist); throws FileError when it cannot be written.
void write_sdf_world(const World& world, const std::filesystem::path& file);

}  // namespace bipednav::sim
