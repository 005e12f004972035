#include "bipednav/sim/shape_tessellation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "bipednav/common/error.hpp"

namespace bipednav::sim {
namespace {

using Vec3f = Eigen::Vector3f;

int add_vertex(TriangleSoup& m, double x, double y, double z) {
  m.vertices.emplace_back(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
  return static_cast<int>(m.vertices.size()) - 1;
}

void add_quad(TriangleSoup& m, int a, int b, int c, int d) {
  m.triangles.emplace_back(a, b, c);
  m.triangles.emplace_back(a, c, d);
}

TriangleSoup box_mesh(const Box& b) {
  require(b.size_m.allFinite() && (b.size_m.array() > 0).all(), "Box.size_m", "three positive sizes");
  TriangleSoup m;
  const Eigen::Vector3d h = 0.5 * b.size_m;
  for (int i = 0; i < 8; ++i)
    add_vertex(m, (i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(), (i & 4) ? h.z() : -h.z());
  // Faces as corner indices (bit 0 = +x, bit 1 = +y, bit 2 = +z), outward winding.
  add_quad(m, 0, 2, 3, 1);  // -z
  add_quad(m, 4, 5, 7, 6);  // +z
  add_quad(m, 0, 1, 5, 4);  // -y
  add_quad(m, 2, 6, 7, 3);  // +y
  add_quad(m, 0, 4, 6, 2);  // -x
  add_quad(m, 1, 3, 7, 5);  // +x
  return m;
}

// Radius of the polygon vertices that makes the facets straddle the circle of radius r.
double straddle_radius(double r, int n) {
  const double c = std::cos(std::numbers::pi / n);
  return 2.0 * r / (1.0 + c);
}

TriangleSoup cylinder_mesh(const Cylinder& cyl, const TessellationParams& p) {
  require(cyl.radius_m > 0 && cyl.length_m > 0 && std::isfinite(cyl.radius_m) && std::isfinite(cyl.length_m),
          "Cylinder", "positive radius_m and length_m");
  TriangleSoup m;
  const int n = circle_segments(cyl.radius_m, p);
  const double rv = straddle_radius(cyl.radius_m, n), hz = 0.5 * cyl.length_m;
  const int bottom_c = add_vertex(m, 0, 0, -hz), top_c = add_vertex(m, 0, 0, hz);
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n;
    add_vertex(m, rv * std::cos(a), rv * std::sin(a), -hz);
    add_vertex(m, rv * std::cos(a), rv * std::sin(a), hz);
  }
  for (int i = 0; i < n; ++i) {
    const int b0 = 2 + 2 * i, t0 = b0 + 1, b1 = 2 + 2 * ((i + 1) % n), t1 = b1 + 1;
    add_quad(m, b0, b1, t1, t0);
    m.triangles.emplace_back(bottom_c, b1, b0);
    m.triangles.emplace_back(top_c, t0, t1);
  }
  return m;
}

TriangleSoup sphere_mesh(const Sphere& s, const TessellationParams& p) {
  require(s.radius_m > 0 && std::isfinite(s.radius_m), "Sphere.radius_m", "a positive radius");
  TriangleSoup m;
  // A quad's centre lies inside the sphere by both half-angles; a smaller per-axis error keeps
  // the combined deviation within the bound.
  TessellationParams half = p;
  half.max_chord_error_m = 0.5 * p.max_chord_error_m;
  const int n_lon = circle_segments(s.radius_m, half);
  const int n_lat = std::max(4, n_lon / 2);
  const double a_lon = std::numbers::pi / n_lon, a_lat = 0.5 * std::numbers::pi / n_lat;
  const double rv = 2.0 * s.radius_m / (1.0 + std::cos(a_lon) * std::cos(a_lat));
  for (int j = 0; j <= n_lat; ++j) {
    const double el = -0.5 * std::numbers::pi + std::numbers::pi * j / n_lat;
    for (int i = 0; i < n_lon; ++i) {
      const double az = 2.0 * std::numbers::pi * i / n_lon;
      add_vertex(m, rv * std::cos(el) * std::cos(az), rv * std::cos(el) * std::sin(az), rv * std::sin(el));
    }
  }
  for (int j = 0; j < n_lat; ++j)
    for (int i = 0; i < n_lon; ++i) {
      const int i1 = (i + 1) % n_lon;
      add_quad(m, j * n_lon + i, j * n_lon + i1, (j + 1) * n_lon + i1, (j + 1) * n_lon + i);
    }
  return m;
}

TriangleSoup plane_mesh(const Plane& pl, const TessellationParams& p) {
  require(pl.normal.allFinite() && pl.normal.norm() > 1e-12, "Plane.normal", "a non-zero normal");
  require(pl.size_m.allFinite() && (pl.size_m.array() >= 0).all(), "Plane.size_m", "sizes >= 0 (0 = unbounded)");
  const Eigen::Vector3d n = pl.normal.normalized();
  const Eigen::Matrix3d R = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), n).toRotationMatrix();
  const double hx = pl.size_m.x() > 0 ? 0.5 * pl.size_m.x() : p.unbounded_plane_half_size_m;
  const double hy = pl.size_m.y() > 0 ? 0.5 * pl.size_m.y() : p.unbounded_plane_half_size_m;
  TriangleSoup m;
  for (const auto& [sx, sy] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
    const Eigen::Vector3d v = R * Eigen::Vector3d(sx * hx, sy * hy, 0.0);
    add_vertex(m, v.x(), v.y(), v.z());
  }
  add_quad(m, 0, 1, 2, 3);
  return m;
}

TriangleSoup mesh_copy(const Mesh& mesh) {
  TriangleSoup m;
  m.vertices = mesh.vertices;
  const int nv = static_cast<int>(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    require(t.minCoeff() >= 0 && t.maxCoeff() < nv, "Mesh.triangles", "vertex indices within the vertex list");
    m.triangles.push_back(t);
  }
  for (const auto& v : m.vertices) require(v.allFinite(), "Mesh.vertices", "finite coordinates");
  return m;
}

}  // namespace

void TessellationParams::validate() const {
  require(max_chord_error_m > 0 && std::isfinite(max_chord_error_m), "max_chord_error_m", "> 0");
  require(min_segments >= 3, "min_segments", ">= 3");
  require(max_segments >= min_segments, "max_segments", ">= min_segments");
  require(unbounded_plane_half_size_m > 0, "unbounded_plane_half_size_m", "> 0");
}

void TriangleSoup::append(const TriangleSoup& other, const SE3& T) {
  const int offset = static_cast<int>(vertices.size());
  const Eigen::Isometry3f Tf = T.cast<float>();
  for (const auto& v : other.vertices) vertices.push_back(Tf * v);
  for (const auto& t : other.triangles) triangles.push_back(t.array() + offset);
}

int circle_segments(double radius_m, const TessellationParams& p) {
  // r (1 - cos a) / (1 + cos a) = r tan^2(a / 2) <= e  =>  a <= 2 atan(sqrt(e / r)).
  const double a = 2.0 * std::atan(std::sqrt(p.max_chord_error_m / radius_m));
  const int n = static_cast<int>(std::ceil(std::numbers::pi / a));
  return std::clamp(n, p.min_segments, p.max_segments);
}

TriangleSoup tessellate_shape(const Shape& shape, const TessellationParams& params) {
  return std::visit(
      [&](const auto& s) -> TriangleSoup {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, Box>)
          return box_mesh(s);
        else if constexpr (std::is_same_v<T, Cylinder>)
          return cylinder_mesh(s, params);
        else if constexpr (std::is_same_v<T, Sphere>)
          return sphere_mesh(s, params);
        else if constexpr (std::is_same_v<T, Plane>)
          return plane_mesh(s, params);
        else
          return mesh_copy(s);
      },
      shape);
}

TriangleSoup tessellate(const Geometry& g, const TessellationParams& params) {
  TriangleSoup out;
  out.append(tessellate_shape(g.shape, params), g.T_parent_shape);
  return out;
}

}  // namespace bipednav::sim
