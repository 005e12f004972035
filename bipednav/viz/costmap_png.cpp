#include "bipednav/viz/costmap_png.hpp"

#include <cairo.h>

#include <cstdint>
#include <cstring>
#include <memory>

#include "bipednav/common/error.hpp"

namespace bipednav::viz {

using mapping::Costmap2D;

namespace {

std::uint32_t png_cost_color(std::uint8_t c) {
  const auto rgb = [](unsigned r, unsigned g, unsigned b) { return 0xff000000u | (r << 16) | (g << 8) | b; };
  if (c == mapping::kFree) return rgb(235, 235, 235);
  if (c == mapping::kUnknown) return rgb(160, 160, 160);
  if (c == mapping::kLethal) return rgb(0, 0, 0);
  if (c == mapping::kInscribed) return rgb(120, 20, 150);
  const double t = c / 252.0;  // inflated: light to deep blue
  return rgb(unsigned(200 - 170 * t), unsigned(220 - 170 * t), unsigned(255 - 55 * t));
}

}  // namespace

void write_costmap_png(const std::filesystem::path& path, const Costmap2D& costmap, int scale) {
  if (scale < 1 || scale > 64) throw Error("write_costmap_png: scale must be 1..64 pixels per cell");
  if (costmap.width() <= 0 || costmap.height() <= 0) throw Error("write_costmap_png: empty costmap");
  const int w = costmap.width() * scale, h = costmap.height() * scale;
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> s(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h), cairo_surface_destroy);
  if (cairo_surface_status(s.get()) != CAIRO_STATUS_SUCCESS) throw Error("write_costmap_png: image too large");
  cairo_surface_flush(s.get());
  unsigned char* data = cairo_image_surface_get_data(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  for (int py = 0; py < h; ++py)
    for (int px = 0; px < w; ++px) {
      const std::uint32_t c = png_cost_color(costmap.cost(px / scale, costmap.height() - 1 - py / scale));
      std::memcpy(data + std::size_t(py) * stride + 4 * px, &c, 4);
    }
  cairo_surface_mark_dirty(s.get());
  if (cairo_surface_write_to_png(s.get(), path.string().c_str()) != CAIRO_STATUS_SUCCESS)
    throw FileError(path.string(), "", "cannot write the PNG file");
}

}  // namespace bipednav::viz
