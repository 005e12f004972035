#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace bipednav::io {

// The map_server file format on plain types: the YAML's fields and the image's gray pixels. The
// pixels become costs in mapping/map_io.hpp.

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

// Reads a PGM (P5 8/16-bit or P2) image as 8-bit gray, row 0 at the top.
struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // gray (averaged colour channels)
  std::vector<std::uint8_t> alpha;   // empty, or one per pixel
};
GrayImage read_pgm(const std::filesystem::path& path);
GrayImage read_png_gray(const std::filesystem::path& path);

// A map_server map as stored: its YAML's fields and its image (PGM P5/P2 or PNG, by extension).
// Rotated maps (origin yaw != 0) are rejected. Malformed files raise FileError naming the file and
// the field.
struct MapServerFile {
  MapServerMetadata metadata;
  GrayImage image;
};
MapServerFile read_map_server_file(const std::filesystem::path& yaml_path);

// Writes `image` as `<stem>.pgm` (P5) next to `yaml_path` and the YAML naming it, with the given
// resolution and origin and map_saver's trinary fields (yaw 0, negate 0, occupied_thresh 0.65,
// free_thresh 0.196).
void write_map_server_file(const std::filesystem::path& yaml_path, const GrayImage& image, double resolution_m,
                           double origin_x_m, double origin_y_m);

}  // namespace bipednav::io
