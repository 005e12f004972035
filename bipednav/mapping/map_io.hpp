#pragma once

#include <filesystem>

#include "bipednav/io/heightmap_image.hpp"
#include "bipednav/io/map_server.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/mapping/heightmap.hpp"

namespace bipednav::mapping {

// Maps from files: io/ reads the formats into plain pixels and heights, these make costmaps and
// heightmaps of them.

// Reads a map_server map (YAML + PGM P5/P2 or PNG) into costs the way map_server and the Nav2
// static layer do: p = (255 - gray) / 255 (inverted when negate), p > occupied_thresh -> kLethal,
// p < free_thresh -> kFree, otherwise kUnknown (trinary) or, in scale mode, occupancy
// 99 (p - free) / (occ - free) mapped to cost occupancy / 100 * 254 (a transparent pixel is
// unknown). Image row 0 is the top of the map (largest y). Rotated maps (origin yaw != 0) are
// rejected. Malformed files raise FileError naming the file and the field.
Costmap2D read_map_server(const std::filesystem::path& yaml_path, io::MapServerMetadata* metadata = nullptr);

// Writes `<stem>.yaml` + `<stem>.pgm` next to each other (P5, trinary: kLethal -> 0, kUnknown ->
// 205, every other cost -> 254; occupied_thresh 0.65, free_thresh 0.196, as map_saver does).
void write_map_server(const std::filesystem::path& yaml_path, const Costmap2D& costmap);

// Reads a PNG heightmap (io::read_heightmap_grid: the PNG itself with `params`, or a YAML naming
// it) into a Heightmap: known cells with variance 0, transparent pixels unknown.
Heightmap read_heightmap_image(const std::filesystem::path& file, const io::HeightmapImageParams& params = {});

}  // namespace bipednav::mapping
