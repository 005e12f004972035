#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/planning/local/teb_params.hpp"
#include "bipednav/planning/local/teb_terms.hpp"

namespace bipednav::planning::local {

// An obstacle of eq. 5.15 as a simply connected region: a point (1 vertex), a line segment
// (2 vertices) or a convex polygon (>= 3 vertices, counter-clockwise).
struct Obstacle {
  enum class Kind { kPoint, kLine, kPolygon };
  Kind kind = Kind::kPoint;
  std::vector<Eigen::Vector2d> vertices;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double radius_m = 0.0;  // bounding circle around the centroid
};

// The minimal Euclidean distance rho(s_k, O_l) of eq. 5.15 (negative inside a polygon).
template <typename T>
T obstacle_distance(const Obstacle& o, const T& x, const T& y) {
  return distance_to_polygon(x, y, o.vertices);
}

// The scalar part of obstacle_distance on ceres::Jet arguments (x, y the Jets' scalar parts), bitwise.
inline double jet_value_obstacle_distance(const Obstacle& o, double x, double y) {
  const auto& v = o.vertices;
  if (v.size() == 1) return jet_value_distance_to_point(x, y, v[0]);
  if (v.size() == 2) return jet_value_distance_to_segment(x, y, v[0], v[1]);
  return jet_polygon_nearest(x, y, v).value;
}

// Builds an obstacle from a set of points: a point when the set is smaller than point_max_extent,
// a segment along the principal axis when thinner than line_max_width, else the convex hull.
Obstacle make_obstacle(const std::vector<Eigen::Vector2d>& pts, double half_cell_m, const ObstacleParams& params);

// Convex hull (counter-clockwise, no collinear points) of a point set (Andrew's monotone chain).
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> pts);

// extract_obstacles' buffers, kept between calls by their owner (what they held does not change
// the obstacles).
struct ObstacleScratch {
  std::vector<std::uint8_t> seen;     // per cell: already in a component
  std::vector<std::size_t> stack;     // flood fill
  std::vector<std::size_t> cells;     // the components' cells, component after component, each in scan order
  std::vector<std::size_t> comp_end;  // end of each component in cells (components in scan order)
  std::vector<std::pair<std::pair<long, long>, std::size_t>> keyed;  // (block, position in cells)
  std::vector<Eigen::Vector2d> centres;                              // one component's cell centres
  std::vector<Eigen::Vector2d> pts;                                  // one block's cell centres
  std::vector<std::uint32_t> bucket_start;                           // sort_by_block's counts
  std::vector<std::pair<std::pair<long, long>, std::size_t>> sorted;
};

// Clusters the lethal cells of the costmap into 8-connected components, cuts large ones into
// cluster_block_m blocks and converts each piece with make_obstacle. Deterministic order. Without
// `scratch` the call allocates its own buffers.
std::vector<Obstacle> extract_obstacles(const mapping::Costmap2D& costmap, const ObstacleParams& params,
                                        ObstacleScratch* scratch = nullptr);

// Indices of the (at most k) obstacles nearest to p within max_dist_m, nearest first.
// `candidates`: a buffer for the obstacles within max_dist_m (with their distances), for a caller
// that calls this per band pose to reuse; without it the call allocates its own.
std::vector<int> nearest_obstacles(const std::vector<Obstacle>& obstacles, const Eigen::Vector2d& p, int k,
                                   double max_dist_m, std::vector<std::pair<double, int>>* candidates = nullptr);

}  // namespace bipednav::planning::local
