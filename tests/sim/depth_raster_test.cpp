#include "bipednav/sim/depth_raster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/common/simd4.hpp"
#include "bipednav/sim/depth_camera.hpp"
#include "bipednav/sim/sdf_world.hpp"
#include "bipednav/sim/simulation.hpp"
#include "test_data.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::sim;

// Agreement of the rasteriser with the reference ray caster over many views of a world.
struct Agreement {
  std::size_t pixels = 0;
  std::size_t valid = 0;             // with a depth in the reference
  std::size_t edge = 0;              // pixels on a silhouette edge (see is_edge)
  std::size_t mismatched = 0;        // NaN mask differs or depth differs by more than 1e-4 m
  std::size_t mismatched_inner = 0;  // of those, not on an edge
  double max_inner_error_m = 0.0;
};

bool is_nan(const PointCloud& c, std::size_t i) { return std::isnan(c.points[i].x()); }

// A pixel on a silhouette edge: a 4-neighbour in either image differs from it in NaN mask or
// by a depth step of more than 5 % (the neighbour sees another surface).
bool is_edge(const PointCloud& a, const PointCloud& b, int w, int h, int u, int v) {
  const auto idx = [w](int uu, int vv) { return static_cast<std::size_t>(vv * w + uu); };
  const std::size_t i = idx(u, v);
  const int du[4] = {1, -1, 0, 0}, dv[4] = {0, 0, 1, -1};
  for (const PointCloud* c : {&a, &b})
    for (int k = 0; k < 4; ++k) {
      const int uu = u + du[k], vv = v + dv[k];
      if (uu < 0 || vv < 0 || uu >= w || vv >= h) continue;
      const std::size_t j = idx(uu, vv);
      if (is_nan(*c, i) != is_nan(*c, j)) return true;
      if (!is_nan(*c, i) && std::abs(c->points[i].x() - c->points[j].x()) > 0.05f * c->points[i].x()) return true;
    }
  return false;
}

void compare(const PointCloud& ray, const PointCloud& raster, int w, int h, Agreement& out) {
  ASSERT_EQ(ray.size(), raster.size());
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) {
      const auto i = static_cast<std::size_t>(v * w + u);
      ++out.pixels;
      out.valid += !is_nan(ray, i);
      const bool edge = is_edge(ray, raster, w, h, u, v);
      out.edge += edge;
      const bool nan_a = is_nan(ray, i), nan_b = is_nan(raster, i);
      const double err = nan_a || nan_b ? 0.0 : std::abs(ray.points[i].x() - raster.points[i].x());
      const bool bad = nan_a != nan_b || err > 1e-4;
      out.mismatched += bad;
      if (!edge) {
        out.mismatched_inner += bad;
        if (!bad) out.max_inner_error_m = std::max(out.max_inner_error_m, err);
      }
    }
}

// Renders `views` random views of `world` (camera 0.1-1.6 m up, any yaw, pitch within +-50
// deg, roll within +-10 deg) both ways, at the actor times given.
Agreement agreement(const World& world, double half_x, double half_y, int views, std::uint64_t seed, int width = 424,
                    int height = 240) {
  RayCaster caster(world);
  DepthCameraParams p;
  p.width = width;
  p.height = height;
  p.noise_coeff_per_m = 0.0;
  p.renderer = "raycast";
  DepthCamera ray(p, "cam", 1);
  p.renderer = "raster";
  DepthCamera raster(p, "cam", 1);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Agreement a;
  for (int k = 0; k < views; ++k) {
    caster.set_time(0.7 * k);
    const SE3 T = make_se3(half_x * U(rng), half_y * U(rng), 0.85 + 0.75 * U(rng), 0.17 * U(rng), 0.87 * U(rng),
                           std::numbers::pi * U(rng));
    compare(ray.capture_at(0.0, T, caster), raster.capture_at(0.0, T, caster), p.width, p.height, a);
  }
  return a;
}

void expect_equivalent(const Agreement& a, const char* what, bool mostly_valid = true) {
  const double edge_share = static_cast<double>(a.edge) / static_cast<double>(a.pixels);
  const double mismatch_share = static_cast<double>(a.mismatched) / static_cast<double>(a.pixels);
  std::printf(
      "%s: %zu pixels (%.1f %% valid), %.3f %% on edges, %.4f %% mismatched (%zu off edges), max error off edges %.2e "
      "m\n",
      what, a.pixels, 100.0 * static_cast<double>(a.valid) / static_cast<double>(a.pixels), 100 * edge_share,
      100 * mismatch_share, a.mismatched_inner, a.max_inner_error_m);
  if (mostly_valid) {
    EXPECT_GT(a.valid, a.pixels / 2) << what;
  }
  EXPECT_EQ(a.mismatched_inner, 0u) << what;
  EXPECT_LT(mismatch_share, 1e-3) << what;
  EXPECT_LE(a.max_inner_error_m, 1e-4) << what;
}

// A furnished room with a moving actor: boxes, cylinders, a sphere, a tilted crate, a low
// beam, a ceiling slab, and two actors (a tall box and a cylinder) walking through it.
World furnished_room() {
  World w;
  w.statics.push_back({"ground", SE3::Identity(), Plane{}});
  const double lx = 12.0, ly = 10.0, t = 0.1, h = 2.5;
  w.statics.push_back({"wall_n", make_se3(0, ly / 2, h / 2, 0, 0, 0), Box{{lx, t, h}}});
  w.statics.push_back({"wall_s", make_se3(0, -ly / 2, h / 2, 0, 0, 0), Box{{lx, t, h}}});
  w.statics.push_back({"wall_e", make_se3(lx / 2, 0, h / 2, 0, 0, 0), Box{{t, ly, h}}});
  w.statics.push_back({"wall_w", make_se3(-lx / 2, 0, h / 2, 0, 0, 0), Box{{t, ly, h}}});
  for (const double x : {-3.0, 0.0, 3.0})
    w.statics.push_back({"pillar", make_se3(x, 2.0, 1.0, 0, 0, 0), Cylinder{0.15, 2.0}});
  w.statics.push_back({"crate", make_se3(2.0, -2.0, 0.5, 0.2, 0.1, 0.7), Box{{0.8, 0.6, 0.8}}});
  w.statics.push_back({"ball", make_se3(-2.0, -1.5, 0.4, 0, 0, 0), Sphere{0.4}});
  w.statics.push_back({"beam", make_se3(0.0, -3.0, 1.2, 0, 0, 0), Box{{6.0, 0.1, 0.1}}});
  w.statics.push_back({"slab", make_se3(-4.0, 3.0, 2.0, 0, 0, 0), Box{{2.0, 2.0, 0.05}}});
  Actor box;
  box.name = "box";
  box.parts.push_back({"box", SE3::Identity(), Box{{0.3, 0.3, 1.8}}});
  box.trajectory = {{0, make_se3(-3, -3, 0.9, 0, 0, 0)}, {10, make_se3(3, 3, 0.9, 0, 0, 1.5)}};
  w.actors.push_back(box);
  Actor person;
  person.name = "person";
  person.parts.push_back({"body", make_se3(0, 0, 0.8, 0, 0, 0), Cylinder{0.25, 1.6}});
  person.trajectory = {{0, make_se3(3, -3, 0, 0, 0, 0)}, {10, make_se3(-3, 3, 0, 0, 0, 0)}};
  w.actors.push_back(person);
  return w;
}

TEST(DepthRaster, MatchesRayCastingInAFurnishedRoomWithMovingActors) {
  expect_equivalent(agreement(furnished_room(), 5.5, 4.5, 40, 1), "furnished room + actors");
}

TEST(DepthRaster, MatchesRayCastingInTheTurtlebot3MeshWorld) {
  World w = load_sdf_world(test::source_dir() / "scenarios/worlds/turtlebot3/worlds/turtlebot3_world.world");
  ensure_ground_plane(w);
  expect_equivalent(agreement(w, 2.0, 2.0, 40, 2), "turtlebot3 world");
}

TEST(DepthRaster, MatchesRayCastingAtOddImageSizes) {
  // Rows that are not a multiple of the 4 SIMD lanes, a single column, a single pixel.
  for (const auto& [w, h] : {std::pair{37, 21}, std::pair{5, 3}, std::pair{1, 7}, std::pair{1, 1}})
    expect_equivalent(agreement(furnished_room(), 5.5, 4.5, 20, 4, w, h), "odd size", false);
}

TEST(DepthRaster, MatchesRayCastingFromInsideASolid) {
  // Inside a closed box the ray caster sees the inner (back) faces: nothing may be culled.
  World w;
  w.statics.push_back({"hut", make_se3(0, 0, 1.5, 0, 0, 0.3), Box{{8.0, 6.0, 3.0}}});
  w.statics.push_back({"barrel", make_se3(1.0, 1.0, 1.0, 0, 0, 0), Cylinder{0.3, 2.0}});
  expect_equivalent(agreement(w, 2.0, 1.5, 10, 3), "inside a box");
}

TEST(DepthRaster, ActorsAreDrawnWhereTheyAreNowAndPlanesAnalytically) {
  World w;
  w.statics.push_back({"ground", SE3::Identity(), Plane{}});
  Actor a;
  a.name = "box";
  a.parts.push_back({"box", SE3::Identity(), Box{{1.0, 4.0, 4.0}}});
  a.trajectory = {{0, make_se3(3.5, 0, 1.0, 0, 0, 0)}, {10, make_se3(8.5, 0, 1.0, 0, 0, 0)}};
  a.loop = false;
  w.actors.push_back(a);
  RayCaster caster(w);
  DepthCameraParams p;
  p.noise_coeff_per_m = 0.0;
  DepthCamera cam(p, "cam", 1);
  const SE3 T = make_se3(0, 0, 1.0, 0, 0, 0);
  const std::size_t centre = static_cast<std::size_t>(p.height / 2 * p.width + p.width / 2);
  for (const double t : {0.0, 5.0}) {
    caster.set_time(t);
    const PointCloud c = cam.capture_at(t, T, caster);
    EXPECT_NEAR(c.points[centre].x(), 3.0 + 0.5 * t, 1e-5);  // the box's near face
  }
  // Bottom row: the ground 1 m below the level camera, at the depth of a ray cast.
  const PointCloud c = cam.capture_at(5.0, T, caster);
  const std::size_t bottom = static_cast<std::size_t>((p.height - 1) * p.width);
  const Eigen::Vector3f r = cam.pixel_ray(0, p.height - 1);
  EXPECT_NEAR(c.points[bottom].x(), r.x() / -r.z(), 1e-5);
}

TEST(DepthRaster, RejectsAnEmptyImageAndAnUnknownRenderer) {
  EXPECT_THROW(DepthRasterizer({}, {1.0f}, 10.0f), Error);
  DepthCameraParams p;
  p.renderer = "opengl";
  EXPECT_THROW(p.validate(), ParamError);
}

}  // namespace
