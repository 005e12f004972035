#include <cairo.h>
#include <gtest/gtest.h>

#include "bipednav/sim/scenario.hpp"
#include "bipednav/sim/world_drawing.hpp"
#include "test_data.hpp"

namespace fs = std::filesystem;
using namespace bipednav;
using namespace bipednav::sim;

TEST(WorldDrawing, FootprintsOfPrimitives) {
  const Geometry box{"b", make_se3(1, 2, 0.5, 0, 0, M_PI / 2), Box{Eigen::Vector3d(2, 1, 1)}};
  const auto fp = footprint(box, SE3::Identity());
  ASSERT_EQ(fp.size(), 1u);
  Bounds2 b;
  for (const auto& p : fp[0]) b.add(p);
  EXPECT_NEAR(b.min_x_m, 0.5, 1e-9);  // rotated 90 deg: 1 m along x, 2 m along y
  EXPECT_NEAR(b.max_y_m, 3.0, 1e-9);
  // Above 2 m (an overhang) or under the ground: no footprint.
  EXPECT_TRUE(footprint({"high", make_se3(0, 0, 3, 0, 0, 0), Box{}}, SE3::Identity()).empty());
  EXPECT_TRUE(footprint({"ground", SE3::Identity(), Plane{}}, SE3::Identity()).empty());
  const auto cyl = footprint({"c", make_se3(0, 0, 1, 0, 0, 0), Cylinder{0.15, 2.0}}, SE3::Identity());
  ASSERT_EQ(cyl.size(), 1u);
  for (const auto& p : cyl[0]) EXPECT_NEAR(p.norm(), 0.15, 1e-9);
}

TEST(WorldDrawing, HexagonFigureShowsCylindersAndWalls) {
  const Scenario s = load_scenario(test::source_dir() / "scenarios/hexagon_static.yaml");
  viz::CanvasParams cp;
  cp.min_x_m = s.bounds.min_x_m, cp.max_x_m = s.bounds.max_x_m;
  cp.min_y_m = s.bounds.min_y_m, cp.max_y_m = s.bounds.max_y_m;
  cp.pixels_per_m = 40;
  viz::Canvas canvas(cp);
  draw_world(canvas, s.world);
  const fs::path png = fs::temp_directory_path() / "bipednav_world_drawing.png";
  canvas.write_png(png);
  cairo_surface_t* img = cairo_image_surface_create_from_png(png.string().c_str());
  ASSERT_EQ(cairo_surface_status(img), CAIRO_STATUS_SUCCESS);
  const auto grey = [&](double x, double y) {
    const Eigen::Vector2d q = canvas.to_pixel({x, y});
    const unsigned char* d = cairo_image_surface_get_data(img);
    return d[static_cast<int>(q.y()) * cairo_image_surface_get_stride(img) + 4 * static_cast<int>(q.x())];
  };
  EXPECT_LT(grey(0.0, 0.0), 128);    // the centre cylinder
  EXPECT_LT(grey(0.0, 2.7), 128);    // inside the wall ring (apothem 2.54 .. 2.86)
  EXPECT_EQ(grey(0.55, 0.55), 255);  // free space between cylinders
  EXPECT_EQ(grey(0.0, 2.3), 255);    // just inside the wall
  cairo_surface_destroy(img);
}
