#pragma once

#include "bipednav/common/error.hpp"
#include "bipednav/mapping/heightmap.hpp"
#include "bipednav/sim/raycaster.hpp"

namespace bipednav::sim {

// The true terrain as a heightmap: per cell the first surface hit by a ray cast straight down
// from `top_z_m` through the cell centre (variance 0; NaN where nothing is hit). Exact for the
// 2.5D worlds of the footstep scenarios (boxes standing on the ground: no overhangs), up to the
// resolution; used as the ground truth of the humanoid walker.
mapping::Heightmap true_heightmap(const RayCaster& caster, const mapping::GridGeometry& geometry, double top_z_m);

}  // namespace bipednav::sim
