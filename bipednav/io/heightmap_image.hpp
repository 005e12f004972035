#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

namespace bipednav::io {

// How grey values of a heightmap image become heights (grid_map's image_to_gridmap convention):
// height = min + v / 255 * (max - min); fully transparent pixels are unknown. Image row 0 is the
// map's top (largest y); the map's origin is its lower-left corner.
struct HeightmapImageParams {
  double resolution_m = 0.02;
  double min_height_m = -0.5;
  double max_height_m = 1.0;
  double origin_x_m = 0.0;
  double origin_y_m = 0.0;

  void validate() const;
};

// The heights of a heightmap image, row-major with row 0 at the image's top; params as used (the
// YAML's when reading one). mapping/map_io.hpp makes a Heightmap of it.
struct HeightmapGrid {
  int width = 0;
  int height = 0;
  HeightmapImageParams params;
  std::vector<float> heights;       // width * height, NaN where not known
  std::vector<std::uint8_t> known;  // width * height: 0 where the pixel is fully transparent
};

// Reads a PNG heightmap. `file` is the PNG itself (using `params`), or a YAML file with keys
// image (relative to the YAML), resolution_m, min_height_m, max_height_m, origin_x_m, origin_y_m.
// Throws FileError naming the file and the field for unreadable or malformed input.
HeightmapGrid read_heightmap_grid(const std::filesystem::path& file, const HeightmapImageParams& params = {});

}  // namespace bipednav::io
