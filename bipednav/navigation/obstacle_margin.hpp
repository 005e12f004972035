#pragma once

#include "bipednav/mapping/heightmap.hpp"

namespace bipednav::navigation {

// Grows what the robot cannot step onto by a safety margin for the footstep planner, whose
// whole-body check has none: a cell is an obstacle edge when it stands more than `min_step_m`
// above the lowest known cell of its 3 x 3 neighbourhood (a wall's face, a block's side; bars
// and stair risers lower than that stay as they are), and every cell within `margin_m` of an
// edge cell takes that cell's height if it is lower (unknown cells too). The margin covers the
// robot's execution and localization error next to walls.
mapping::Heightmap inflate_obstacles(const mapping::Heightmap& map, double margin_m, double min_step_m);

}  // namespace bipednav::navigation
