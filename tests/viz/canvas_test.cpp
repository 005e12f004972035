#include "bipednav/viz/canvas.hpp"

#include <cairo.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>

#include "bipednav/common/error.hpp"

namespace fs = std::filesystem;
using namespace bipednav;
using namespace bipednav::viz;

namespace {

// Reads back one pixel (ARGB32, premultiplied) of a written PNG.
std::uint32_t pixel(const fs::path& png, int x, int y) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.string().c_str());
  EXPECT_EQ(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const std::uint32_t v = *reinterpret_cast<const std::uint32_t*>(data + y * cairo_image_surface_get_stride(s) + 4 * x);
  cairo_surface_destroy(s);
  return v;
}

CanvasParams window_10x4() {
  CanvasParams p;
  p.min_x_m = 0, p.max_x_m = 10, p.min_y_m = -2, p.max_y_m = 2;
  p.pixels_per_m = 20, p.margin_px = 5;
  return p;
}

}  // namespace

TEST(Canvas, PngHasExpectedSizeAndYUp) {
  Canvas c(window_10x4());
  EXPECT_EQ(c.width_px(), 210);
  EXPECT_EQ(c.height_px(), 90);
  EXPECT_TRUE(c.to_pixel({0, 2}).isApprox(Eigen::Vector2d(5, 5)));
  EXPECT_TRUE(c.to_pixel({10, -2}).isApprox(Eigen::Vector2d(205, 85)));
  // A black square in the upper-left quarter of the world (y > 0 is the top of the picture).
  c.polygon({{1, 1}, {2, 1}, {2, 2}, {1, 2}}, colors::kBlack);
  c.circle({8, -1}, 0.5, colors::kRed);
  c.arrow(Pose2{5, 0, 0}, 1.0, colors::kBlue);
  c.points({{3, -1}, {3.5, -1}}, colors::kGreen, 3);
  c.text({4, 1}, "label", colors::kBlack);
  const fs::path png = fs::temp_directory_path() / "bipednav_canvas_test.png";
  c.write_png(png);
  cairo_surface_t* s = cairo_image_surface_create_from_png(png.string().c_str());
  EXPECT_EQ(cairo_image_surface_get_width(s), 210);
  EXPECT_EQ(cairo_image_surface_get_height(s), 90);
  cairo_surface_destroy(s);
  const Eigen::Vector2d in_square = c.to_pixel({1.5, 1.5});
  EXPECT_EQ(pixel(png, static_cast<int>(in_square.x()), static_cast<int>(in_square.y())), 0xff000000u);
  const Eigen::Vector2d below = c.to_pixel({1.5, -1.5});
  EXPECT_EQ(pixel(png, static_cast<int>(below.x()), static_cast<int>(below.y())), 0xffffffffu);
  const Eigen::Vector2d in_circle = c.to_pixel({8, -1});
  EXPECT_EQ(pixel(png, static_cast<int>(in_circle.x()), static_cast<int>(in_circle.y())) & 0x00ff0000u, 0x00d90000u);
}

TEST(Canvas, GridCellsGetTheirCostClassColour) {
  mapping::GridGeometry g;
  g.width = 4, g.height = 2, g.resolution_m = 1.0, g.origin_x_m = 0, g.origin_y_m = -2;
  mapping::Costmap2D map(g);
  map.set_cost(0, 0, mapping::kLethal);   // world (0.5, -1.5)
  map.set_cost(3, 1, mapping::kUnknown);  // world (3.5, -0.5)
  Canvas c(window_10x4());
  CostColors palette;
  palette.unknown = colors::kRed;
  c.grid(map, palette);
  const fs::path png = fs::temp_directory_path() / "bipednav_canvas_grid.png";
  c.write_png(png);
  const auto px = [&](double x, double y) {
    const Eigen::Vector2d q = c.to_pixel({x, y});
    return pixel(png, static_cast<int>(q.x()), static_cast<int>(q.y()));
  };
  EXPECT_EQ(px(0.5, -1.5), 0xff000000u);  // lethal black
  EXPECT_EQ(px(1.5, -1.5), 0xffffffffu);  // free: transparent over the white background
  EXPECT_EQ(px(3.5, -0.5) & 0x00ffffffu, 0x00d91a1au);
  EXPECT_EQ(cost_color(mapping::kInscribed, palette).b, palette.inscribed.b);
}

TEST(Canvas, BadInputs) {
  Canvas c(window_10x4());
  c.line({0, 0}, {10, 0}, colors::kBlack);
  EXPECT_THROW(c.write_png("/nonexistent_dir/x.png"), FileError);
  CanvasParams bad = window_10x4();
  bad.max_x_m = bad.min_x_m;
  EXPECT_THROW(Canvas{bad}, ParamError);
}
