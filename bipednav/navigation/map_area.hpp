#pragma once

#include "bipednav/mapping/grid_geometry.hpp"

namespace bipednav::navigation {

// The rectangle of the map frame that a navigator's global map covers. A robot's node takes it from
// its parameters; the closed-loop runner and the simulator node take it from a scenario's bounds.
struct MapArea {
  double min_x_m = -10.0, min_y_m = -10.0, max_x_m = 10.0, max_y_m = 10.0;
  double margin_m = 0.0;  // added on every side (room to plan around obstacles at the edge)

  // Rejects non-finite corners, min >= max and a negative margin.
  void validate() const;
};

// The global map's grid over `area` widened by its margin, at `resolution_m`: the origin is the
// multiple of the resolution at or below the widened lower-left corner, and the grid has as many
// cells as reach the widened upper-right corner. validate()s the area; a resolution <= 0 or more
// than a million cells a side is a ParamError.
mapping::GridGeometry global_grid_for(const MapArea& area, double resolution_m);

}  // namespace bipednav::navigation
