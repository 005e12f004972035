#pragma once

#include <filesystem>
#include <string>

#include "bipednav/mapping/costmap2d.hpp"

namespace bipednav::io {

// The fields of a ROS map_server YAML file.
struct MapServerMetadata {
  std::string image;  // relative to the YAML's directory
  double resolution_m = 0.05;
  double origin_x_m = 0.0, origin_y_m = 0.0, origin_yaw_rad = 0.0;
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  std::string mode = "trinary";  // trinary | scale
};

// Reads a map_server map (YAML + PGM P5/P2 or PNG) into costs the way map_server and the Nav2
// static layer do: p = (255 - gray) / 255 (inverted when negate), p > occupied_thresh -> kLethal,
// p < free_thresh -> kFree, otherwise kUnknown (trinary) or, in scale mode, occupancy
// 99 (p - free) / (occ - free) mapped to cost occupancy / 100 * 254 (a transparent pixel is
// unknown). Image row 0 is the top of the map (largest y). Rotated maps (origin yaw != 0) are
// rejected. Malformed files raise FileError naming the file and the field.
mapping::Costmap2D read_map_server(const std::filesystem::path& yaml_path, MapServerMetadata* metadata = nullptr);

// Writes `<stem>.yaml` + `<stem>.pgm` next to each other (P5, trinary: kLethal -> 0, kUnknown ->
// 205, every other cost -> 254; occupied_thresh 0.65, free_thresh 0.196, as map_saver does).
void write_map_server(const std::filesystem::path& yaml_path, const mapping::Costmap2D& costmap);

// Reads a PGM (P5 8/16-bit or P2) image as 8-bit gray, row 0 at the top.
struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // gray (averaged colour channels)
  std::vector<std::uint8_t> alpha;   // empty, or one per pixel
};
GrayImage read_pgm(const std::filesystem::path& path);
GrayImage read_png_gray(const std::filesystem::path& path);

// Renders costs as a colour PNG (free light grey, unknown mid grey, lethal black, inscribed
// purple, inflated costs shades of blue), `scale` pixels per cell, north up.
void write_costmap_png(const std::filesystem::path& path, const mapping::Costmap2D& costmap, int scale = 1);

}  // namespace bipednav::io
