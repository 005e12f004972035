#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "bipednav/common/se3.hpp"
#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

// The part of an obstacle inside a horizontal slab z in [z_lo, z_hi], projected onto the
// ground: a disc (vertical cylinders, spheres) or a convex polygon (counter-clockwise; one
// vertex = a point, two = a segment).
struct Footprint2D {
  enum class Kind { Disc, Polygon };
  Kind kind = Kind::Polygon;
  Eigen::Vector2d center{0, 0};
  double radius_m = 0.0;
  std::vector<Eigen::Vector2d> polygon;
  Eigen::Vector2d bbox_min{0, 0}, bbox_max{0, 0};
};

// Signed distance from p to the footprint (negative inside).
double signed_distance(const Footprint2D& f, const Eigen::Vector2d& p);
// The point of the footprint's boundary nearest to p.
Eigen::Vector2d closest_point(const Footprint2D& f, const Eigen::Vector2d& p);

// Convex hull (counter-clockwise, no collinear points) of 2D points (Andrew's monotone chain).
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> pts);

// Clips a 3D polygon to the slab z in [z_lo, z_hi] (Sutherland-Hodgman on both planes).
std::vector<Eigen::Vector3d> clip_to_slab(const std::vector<Eigen::Vector3d>& poly, double z_lo, double z_hi);

// Footprints of geometry `g` placed at T_world_parent * g.T_parent_shape, within the slab.
// Convex shapes give one footprint (exact for boxes, vertical cylinders and spheres; tilted
// cylinders via 2 mm tessellation); meshes give one per triangle crossing the slab.
std::vector<Footprint2D> slab_footprints(const Geometry& g, const SE3& T_world_parent, double z_lo, double z_hi);

}  // namespace bipednav::sim
