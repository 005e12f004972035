#pragma once

#include <filesystem>

#include "bipednav/mapping/costmap2d.hpp"

namespace bipednav::viz {

// Renders costs as a colour PNG (free light grey, unknown mid grey, lethal black, inscribed
// purple, inflated costs shades of blue), `scale` pixels per cell, north up.
void write_costmap_png(const std::filesystem::path& path, const mapping::Costmap2D& costmap, int scale = 1);

}  // namespace bipednav::viz
