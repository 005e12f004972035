#include "bipednav/sim/footprint2d.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bipednav/sim/shape_tessellation.hpp"

namespace bipednav::sim {
namespace {

using V2 = Eigen::Vector2d;
using V3 = Eigen::Vector3d;

double cross(const V2& o, const V2& a, const V2& b) { return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x(); }

V2 closest_on_segment(const V2& a, const V2& b, const V2& p) {
  const V2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + s * ab;
}

Footprint2D make_polygon(std::vector<V2> hull) {
  Footprint2D f;
  f.kind = Footprint2D::Kind::Polygon;
  f.polygon = std::move(hull);
  f.bbox_min = f.bbox_max = f.polygon.front();
  for (const V2& v : f.polygon) {
    f.bbox_min = f.bbox_min.cwiseMin(v);
    f.bbox_max = f.bbox_max.cwiseMax(v);
  }
  return f;
}

Footprint2D make_disc(const V2& c, double r) {
  Footprint2D f;
  f.kind = Footprint2D::Kind::Disc;
  f.center = c;
  f.radius_m = r;
  f.bbox_min = c.array() - r;
  f.bbox_max = c.array() + r;
  return f;
}

// Slab-clipped, projected points of one triangle, appended to pts.
void append_clipped(const TriangleSoup& soup, const Eigen::Vector3i& t, const SE3& T, double z_lo, double z_hi,
                    std::vector<V2>& pts) {
  std::vector<V3> tri;
  for (int k = 0; k < 3; ++k) tri.push_back(T * soup.vertices[t[k]].cast<double>());
  for (const V3& q : clip_to_slab(tri, z_lo, z_hi)) pts.emplace_back(q.x(), q.y());
}

bool is_vertical(const SE3& T) { return std::abs(T.linear()(2, 2)) > 1.0 - 1e-9; }

}  // namespace

std::vector<V2> convex_hull(std::vector<V2> pts) {
  std::sort(pts.begin(), pts.end(),
            [](const V2& a, const V2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.size() < 3) return pts;
  std::vector<V2> h(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, lo = k + 1; i-- > 0;) {
    while (k >= lo && cross(h[k - 2], h[k - 1], pts[i]) <= 0) --k;
    h[k++] = pts[i];
  }
  h.resize(k - 1);
  return h;
}

std::vector<V3> clip_to_slab(const std::vector<V3>& poly, double z_lo, double z_hi) {
  auto clip = [](const std::vector<V3>& in, double z0, double sign) {
    std::vector<V3> out;
    for (std::size_t i = 0; i < in.size(); ++i) {
      const V3& a = in[i];
      const V3& b = in[(i + 1) % in.size()];
      const double da = sign * (a.z() - z0), db = sign * (b.z() - z0);
      if (da >= 0) out.push_back(a);
      if ((da >= 0) != (db >= 0)) out.push_back(a + (b - a) * (da / (da - db)));
    }
    return out;
  };
  return clip(clip(poly, z_lo, 1.0), z_hi, -1.0);
}

V2 closest_point(const Footprint2D& f, const V2& p) {
  if (f.kind == Footprint2D::Kind::Disc) {
    const V2 d = p - f.center;
    const double n = d.norm();
    return n > 0 ? V2(f.center + d * (f.radius_m / n)) : V2(f.center + V2(f.radius_m, 0));
  }
  const auto& poly = f.polygon;
  if (poly.size() == 1) return poly[0];
  V2 best = poly[0];
  double best_d2 = std::numeric_limits<double>::infinity();
  const std::size_t edges = poly.size() == 2 ? 1 : poly.size();
  for (std::size_t i = 0; i < edges; ++i) {
    const V2 q = closest_on_segment(poly[i], poly[(i + 1) % poly.size()], p);
    const double d2 = (q - p).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = q;
  }
  return best;
}

double signed_distance(const Footprint2D& f, const V2& p) {
  if (f.kind == Footprint2D::Kind::Disc) return (p - f.center).norm() - f.radius_m;
  const double d = (closest_point(f, p) - p).norm();
  if (f.polygon.size() < 3) return d;
  for (std::size_t i = 0; i < f.polygon.size(); ++i)
    if (cross(f.polygon[i], f.polygon[(i + 1) % f.polygon.size()], p) < 0) return d;
  return -d;
}

std::vector<Footprint2D> slab_footprints(const Geometry& g, const SE3& T_world_parent, double z_lo, double z_hi) {
  const SE3 T = T_world_parent * g.T_parent_shape;
  const V3 c = T.translation();
  std::vector<Footprint2D> out;
  if (const auto* s = std::get_if<Sphere>(&g.shape)) {
    const double dz = c.z() - std::clamp(c.z(), z_lo, z_hi);
    if (std::abs(dz) < s->radius_m)
      out.push_back(make_disc(c.head<2>(), std::sqrt(s->radius_m * s->radius_m - dz * dz)));
    return out;
  }
  if (const auto* cyl = std::get_if<Cylinder>(&g.shape); cyl && is_vertical(T)) {
    if (c.z() - 0.5 * cyl->length_m <= z_hi && c.z() + 0.5 * cyl->length_m >= z_lo)
      out.push_back(make_disc(c.head<2>(), cyl->radius_m));
    return out;
  }
  TessellationParams coarse;
  coarse.max_chord_error_m = 2e-3;
  const TriangleSoup soup = tessellate_shape(g.shape, coarse);
  if (std::holds_alternative<Mesh>(g.shape)) {
    for (const auto& t : soup.triangles) {
      std::vector<V2> pts;
      append_clipped(soup, t, T, z_lo, z_hi, pts);
      if (!pts.empty()) out.push_back(make_polygon(convex_hull(std::move(pts))));
    }
    return out;
  }
  // A convex body's footprint is the hull of its clipped faces.
  std::vector<V2> pts;
  for (const auto& t : soup.triangles) append_clipped(soup, t, T, z_lo, z_hi, pts);
  if (!pts.empty()) out.push_back(make_polygon(convex_hull(std::move(pts))));
  return out;
}

}  // namespace bipednav::sim
