#include "bipednav/mapping/map_io.hpp"

#include <cstdint>

namespace bipednav::mapping {

namespace {

// map_server's occupancy of one pixel (100, 0..99 in scale mode, 0, -1 unknown) as a cost.
std::uint8_t pixel_cost(double gray, int alpha, const io::MapServerMetadata& m) {
  if (m.negate) gray = 255.0 - gray;
  const double occ = (255.0 - gray) / 255.0;
  if (occ > m.occupied_thresh) return kLethal;
  if (occ < m.free_thresh) return kFree;
  if (m.mode == "trinary" || alpha == 0) return kUnknown;
  const int occupancy = static_cast<int>(99.0 * (occ - m.free_thresh) / (m.occupied_thresh - m.free_thresh));
  // Nav2 static layer (trinary_costmap: false): cost = occupancy / 100 * LETHAL_OBSTACLE.
  return static_cast<std::uint8_t>(occupancy / 100.0 * kLethal);
}

}  // namespace

Costmap2D read_map_server(const std::filesystem::path& yaml_path, io::MapServerMetadata* metadata) {
  const io::MapServerFile file = io::read_map_server_file(yaml_path);
  const io::MapServerMetadata& m = file.metadata;
  const io::GrayImage& img = file.image;
  Costmap2D map({img.width, img.height, m.resolution_m, m.origin_x_m, m.origin_y_m}, kUnknown);
  for (int row = 0; row < img.height; ++row)
    for (int x = 0; x < img.width; ++x) {
      const std::size_t i = std::size_t(row) * img.width + x;
      map.set_cost(x, img.height - 1 - row, pixel_cost(img.pixels[i], img.alpha.empty() ? 255 : img.alpha[i], m));
    }
  if (metadata) *metadata = m;
  return map;
}

void write_map_server(const std::filesystem::path& yaml_path, const Costmap2D& costmap) {
  io::GrayImage img;
  img.width = costmap.width();
  img.height = costmap.height();
  img.pixels.resize(std::size_t(img.width) * img.height);
  for (int row = 0; row < img.height; ++row)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t c = costmap.cost(x, img.height - 1 - row);
      img.pixels[std::size_t(row) * img.width + x] = c == kLethal ? 0 : (c == kUnknown ? 205 : 254);
    }
  const GridGeometry& g = costmap.geometry();
  io::write_map_server_file(yaml_path, img, g.resolution_m, g.origin_x_m, g.origin_y_m);
}

Heightmap read_heightmap_image(const std::filesystem::path& file, const io::HeightmapImageParams& params) {
  const io::HeightmapGrid grid = io::read_heightmap_grid(file, params);
  const io::HeightmapImageParams& p = grid.params;
  Heightmap m({grid.width, grid.height, p.resolution_m, p.origin_x_m, p.origin_y_m});
  for (int row = 0; row < grid.height; ++row)
    for (int x = 0; x < grid.width; ++x) {
      const std::size_t i = std::size_t(row) * grid.width + x;
      if (grid.known[i]) m.set(x, grid.height - 1 - row, grid.heights[i], 0.0f);
    }
  return m;
}

}  // namespace bipednav::mapping
