#pragma once

#include <Eigen/Core>
#include <filesystem>

#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

// Loads a triangle mesh (Collada .dae, STL, OBJ, anything libassimp reads) into one Mesh in
// metres, with every node transform of the file applied and each vertex multiplied by `scale`
// (SDF <mesh><scale>). Collada <unit> is honoured; <up_axis> is ignored, as Gazebo does (the
// turtlebot3 meshes say Y_UP but hold z-up data). Throws FileError when the file is missing,
// unreadable or has no triangles.
Mesh load_mesh(const std::filesystem::path& file, const Eigen::Vector3d& scale = Eigen::Vector3d::Ones());

}  // namespace bipednav::sim
