#pragma once

#include <Eigen/Core>
#include <vector>

#include "bipednav/common/se3.hpp"
#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

// How finely curved shapes become triangles. Vertices of curved surfaces are pushed out so the
// faceted surface straddles the true one: the radial error is at most max_chord_error_m.
struct TessellationParams {
  double max_chord_error_m = 5e-4;
  int min_segments = 16;
  int max_segments = 1024;
  double unbounded_plane_half_size_m = 1000.0;  // an SDF plane of size 0 becomes this large quad

  void validate() const;
};

// An indexed triangle mesh in float precision (what Embree consumes).
struct TriangleSoup {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;

  std::size_t size() const { return triangles.size(); }
  // Appends `other` with its vertices mapped through T.
  void append(const TriangleSoup& other, const SE3& T = SE3::Identity());
};

// Number of segments of a circle of radius r so that the outward-shifted polygon deviates at
// most `max_error` from the circle (error = r (1 - cos a) / (1 + cos a), a = pi / n).
int circle_segments(double radius_m, const TessellationParams& params);

// The shape of `g` as triangles in g's parent frame (T_parent_shape applied).
TriangleSoup tessellate(const Geometry& g, const TessellationParams& params = {});

// The shape alone, in its own frame.
TriangleSoup tessellate_shape(const Shape& shape, const TessellationParams& params = {});

}  // namespace bipednav::sim
