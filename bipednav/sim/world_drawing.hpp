#pragma once

#include <Eigen/Core>
#include <vector>

#include "bipednav/sim/world.hpp"
#include "bipednav/viz/canvas.hpp"

namespace bipednav::sim {

using Polygon2 = std::vector<Eigen::Vector2d>;

// Axis-aligned x/y extent of something in the world frame.
struct Bounds2 {
  double min_x_m = 0.0, min_y_m = 0.0, max_x_m = 0.0, max_y_m = 0.0;
  bool empty = true;

  void add(const Eigen::Vector2d& p);
  void add(const Bounds2& other);
  Bounds2 inflated(double margin_m) const;
};

// Top-view footprint of a geometry placed at T_world_parent, counting only the parts that lie
// between the ground (z > 0.02 m) and `max_z_m`: boxes, cylinders and spheres as the convex hull
// of their projection; meshes as their projected triangles. Horizontal planes (the ground) have
// none; a vertical bounded plane gives its thin outline.
std::vector<Polygon2> footprint(const Geometry& geometry, const SE3& T_world_parent, double max_z_m = 2.0);

// Extent of the world's footprints (statics, and actors along their whole trajectory).
Bounds2 world_bounds(const World& world, double max_z_m = 2.0);

struct WorldStyle {
  viz::Color static_fill{0.35, 0.35, 0.35, 1.0};
  viz::Color actor_fill{0.9, 0.45, 0.1, 0.9};
  viz::Color actor_path{0.9, 0.45, 0.1, 0.5};
  double max_z_m = 2.0;
  // Shade each static by the height of its top (low_fill at the ground, static_fill at
  // full_height_m and above), lowest first, outlined: stairs read as steps, not as one wall.
  bool shade_by_height = false;
  viz::Color low_fill{0.88, 0.88, 0.88, 1.0};
  double full_height_m = 1.0;
};

// The height of a geometry's top placed at T_world_parent (0 for planes).
double top_height_m(const Geometry& geometry, const SE3& T_world_parent);
// The colour of a static whose top is at `top_m` under a height-shaded style.
viz::Color height_fill(const WorldStyle& style, double top_m);

// Draws the static footprints, and the actors at time `t_s` with their trajectories.
void draw_world(viz::Canvas& canvas, const World& world, double t_s = 0.0, const WorldStyle& style = {});

}  // namespace bipednav::sim
