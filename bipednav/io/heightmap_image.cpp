#include "bipednav/io/heightmap_image.hpp"

#include <cairo.h>

#include <cmath>
#include <limits>
#include <memory>
#include <system_error>

#include "bipednav/common/error.hpp"
#include "bipednav/io/param_reader.hpp"

namespace bipednav::io {

void HeightmapImageParams::validate() const {
  require(resolution_m > 0.0 && std::isfinite(resolution_m), "resolution_m", "> 0");
  require(std::isfinite(min_height_m) && std::isfinite(max_height_m) && max_height_m > min_height_m, "max_height_m",
          "> min_height_m (both finite)");
  require(std::isfinite(origin_x_m) && std::isfinite(origin_y_m), "origin_x_m/origin_y_m", "finite");
}

namespace {

HeightmapGrid read_png(const std::filesystem::path& png, const HeightmapImageParams& p) {
  if (std::error_code ec; !std::filesystem::exists(png, ec)) throw FileError(png.string(), "", "file not found");
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> s(cairo_image_surface_create_from_png(png.c_str()),
                                                                       &cairo_surface_destroy);
  if (cairo_surface_status(s.get()) != CAIRO_STATUS_SUCCESS)
    throw FileError(png.string(), "",
                    std::string("not a readable PNG image: ") + cairo_status_to_string(cairo_surface_status(s.get())));
  const int w = cairo_image_surface_get_width(s.get()), h = cairo_image_surface_get_height(s.get());
  const int stride = cairo_image_surface_get_stride(s.get());
  const cairo_format_t fmt = cairo_image_surface_get_format(s.get());
  const unsigned char* data = cairo_image_surface_get_data(s.get());
  if (w <= 0 || h <= 0 || !data) throw FileError(png.string(), "", "empty image");
  const std::size_t n = std::size_t(w) * h;
  HeightmapGrid g{w, h, p, std::vector<float>(n, std::numeric_limits<float>::quiet_NaN()),
                  std::vector<std::uint8_t>(n, 0)};
  for (int row = 0; row < h; ++row) {
    for (int col = 0; col < w; ++col) {
      double v = 0.0;
      bool known = true;
      if (fmt == CAIRO_FORMAT_A8) {
        v = data[row * stride + col];
      } else {
        const std::uint32_t px = reinterpret_cast<const std::uint32_t*>(data + row * stride)[col];
        const unsigned a = fmt == CAIRO_FORMAT_ARGB32 ? (px >> 24) & 0xFF : 255;
        known = a > 0;
        // Premultiplied: undo the alpha for a grey value.
        v = a > 0 ? ((px >> 16) & 0xFF) * 255.0 / a : 0.0;
      }
      if (!known) continue;
      const std::size_t i = std::size_t(row) * w + col;
      g.heights[i] = static_cast<float>(p.min_height_m + v / 255.0 * (p.max_height_m - p.min_height_m));
      g.known[i] = 1;
    }
  }
  return g;
}

}  // namespace

HeightmapGrid read_heightmap_grid(const std::filesystem::path& file, const HeightmapImageParams& params) {
  const auto ext = file.extension().string();
  if (ext != ".yaml" && ext != ".yml") {
    params.validate();
    return read_png(file, params);
  }
  ParamReader r = ParamReader::from_file(file);
  if (r.has("resolution") && !r.has("resolution_m"))
    throw FileError(file.string(), "resolution",
                    "this is a map_server occupancy map; a heightmap YAML has image, resolution_m, min_height_m, "
                    "max_height_m (and origin_x_m, origin_y_m): the image's grey levels are heights");
  HeightmapImageParams p = params;
  std::string image;
  r.require("image", image);
  r.get("resolution_m", p.resolution_m);
  r.get("min_height_m", p.min_height_m);
  r.get("max_height_m", p.max_height_m);
  r.get("origin_x_m", p.origin_x_m);
  r.get("origin_y_m", p.origin_y_m);
  r.finish();
  try {
    p.validate();
  } catch (const ParamError& e) {
    throw FileError(file.string(), "", e.what());
  }
  const std::filesystem::path png = file.parent_path() / image;
  if (std::error_code ec; !std::filesystem::is_regular_file(png, ec))
    throw FileError(file.string(), "image", "the image '" + png.string() + "' does not exist");
  return read_png(png, p);
}

}  // namespace bipednav::io
