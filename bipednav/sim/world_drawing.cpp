#include "bipednav/sim/world_drawing.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/sim/footprint2d.hpp"

namespace bipednav::sim {
namespace {

constexpr double kGroundZ_m = 0.02;
constexpr int kCircleSegments = 32;

// Sample points on the surface of a solid shape, in the shape frame.
std::vector<Eigen::Vector3d> solid_samples(const Shape& shape) {
  std::vector<Eigen::Vector3d> s;
  if (const auto* b = std::get_if<Box>(&shape)) {
    for (int i = 0; i < 8; ++i)
      s.emplace_back((i & 1 ? 0.5 : -0.5) * b->size_m.x(), (i & 2 ? 0.5 : -0.5) * b->size_m.y(),
                     (i & 4 ? 0.5 : -0.5) * b->size_m.z());
  } else if (const auto* c = std::get_if<Cylinder>(&shape)) {
    for (int i = 0; i < kCircleSegments; ++i) {
      const double a = 2 * M_PI * i / kCircleSegments;
      for (double z : {-0.5 * c->length_m, 0.5 * c->length_m})
        s.emplace_back(c->radius_m * std::cos(a), c->radius_m * std::sin(a), z);
    }
  } else if (const auto* sp = std::get_if<Sphere>(&shape)) {
    for (int i = 0; i < kCircleSegments; ++i) {
      const double a = 2 * M_PI * i / kCircleSegments;
      for (int j = -3; j <= 3; ++j) {
        const double e = M_PI / 8 * j;
        s.emplace_back(sp->radius_m * std::cos(a) * std::cos(e), sp->radius_m * std::sin(a) * std::cos(e),
                       sp->radius_m * std::sin(e));
      }
    }
  }
  return s;
}

std::vector<Polygon2> mesh_footprint(const Mesh& mesh, const SE3& T, double max_z_m) {
  std::vector<Polygon2> out;
  std::vector<Eigen::Vector3d> v(mesh.vertices.size());
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = T * mesh.vertices[i].cast<double>();
  for (const Eigen::Vector3i& tri : mesh.triangles) {
    const Eigen::Vector3d &a = v[tri[0]], &b = v[tri[1]], &c = v[tri[2]];
    const double z_lo = std::min({a.z(), b.z(), c.z()}), z_hi = std::max({a.z(), b.z(), c.z()});
    if (z_hi <= kGroundZ_m || z_lo >= max_z_m) continue;
    out.push_back({a.head<2>(), b.head<2>(), c.head<2>()});
  }
  return out;
}

std::vector<Polygon2> plane_footprint(const Plane& plane, const SE3& T) {
  const Eigen::Vector3d n = T.linear() * plane.normal;
  if (std::abs(n.z()) > 0.9 || plane.size_m.x() <= 0 || plane.size_m.y() <= 0) return {};
  Polygon2 pts;
  // A bounded plane's local frame: normal along z; its rectangle spans x and y.
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), plane.normal);
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d local((i & 1 ? 0.5 : -0.5) * plane.size_m.x(), (i & 2 ? 0.5 : -0.5) * plane.size_m.y(), 0);
    pts.push_back((T * (q * local)).head<2>());
  }
  return {convex_hull(pts)};
}

}  // namespace

void Bounds2::add(const Eigen::Vector2d& p) {
  if (!p.allFinite()) return;
  if (empty) {
    min_x_m = max_x_m = p.x(), min_y_m = max_y_m = p.y(), empty = false;
    return;
  }
  min_x_m = std::min(min_x_m, p.x()), max_x_m = std::max(max_x_m, p.x());
  min_y_m = std::min(min_y_m, p.y()), max_y_m = std::max(max_y_m, p.y());
}

void Bounds2::add(const Bounds2& o) {
  if (o.empty) return;
  add(Eigen::Vector2d(o.min_x_m, o.min_y_m));
  add(Eigen::Vector2d(o.max_x_m, o.max_y_m));
}

Bounds2 Bounds2::inflated(double margin_m) const {
  if (empty) return *this;
  return {min_x_m - margin_m, min_y_m - margin_m, max_x_m + margin_m, max_y_m + margin_m, false};
}

std::vector<Polygon2> footprint(const Geometry& g, const SE3& T_world_parent, double max_z_m) {
  const SE3 T = T_world_parent * g.T_parent_shape;
  if (const auto* m = std::get_if<Mesh>(&g.shape)) return mesh_footprint(*m, T, max_z_m);
  if (const auto* p = std::get_if<Plane>(&g.shape)) return plane_footprint(*p, T);
  Polygon2 pts;
  double z_lo = 1e18, z_hi = -1e18;
  for (const Eigen::Vector3d& s : solid_samples(g.shape)) {
    const Eigen::Vector3d w = T * s;
    z_lo = std::min(z_lo, w.z()), z_hi = std::max(z_hi, w.z());
    pts.push_back(w.head<2>());
  }
  if (pts.empty() || z_hi <= kGroundZ_m || z_lo >= max_z_m) return {};
  return {convex_hull(pts)};
}

Bounds2 world_bounds(const World& world, double max_z_m) {
  Bounds2 b;
  for (const Geometry& g : world.statics)
    for (const Polygon2& poly : footprint(g, SE3::Identity(), max_z_m))
      for (const auto& p : poly) b.add(p);
  for (const Actor& a : world.actors)
    for (const Waypoint& w : a.trajectory)
      for (const Geometry& g : a.parts)
        for (const Polygon2& poly : footprint(g, w.pose, max_z_m))
          for (const auto& p : poly) b.add(p);
  return b;
}

double top_height_m(const Geometry& g, const SE3& T_world_parent) {
  const SE3 T = T_world_parent * g.T_parent_shape;
  double top = 0.0;
  if (const auto* m = std::get_if<Mesh>(&g.shape)) {
    for (const Eigen::Vector3f& v : m->vertices) top = std::max(top, (T * v.cast<double>()).z());
    return top;
  }
  for (const Eigen::Vector3d& s : solid_samples(g.shape)) top = std::max(top, (T * s).z());
  return top;
}

viz::Color height_fill(const WorldStyle& style, double top_m) {
  const double f = std::clamp(top_m / style.full_height_m, 0.0, 1.0);
  const viz::Color &a = style.low_fill, &b = style.static_fill;
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b), a.a + f * (b.a - a.a)};
}

namespace {

void draw_statics(viz::Canvas& canvas, const World& world, const WorldStyle& style) {
  if (!style.shade_by_height) {
    for (const Geometry& g : world.statics)
      for (const Polygon2& poly : footprint(g, SE3::Identity(), style.max_z_m))
        canvas.polygon(poly, style.static_fill, style.static_fill, 0.5);
    return;
  }
  std::vector<std::pair<double, const Geometry*>> by_height;
  for (const Geometry& g : world.statics) by_height.emplace_back(top_height_m(g, SE3::Identity()), &g);
  std::stable_sort(by_height.begin(), by_height.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [top, g] : by_height)
    for (const Polygon2& poly : footprint(*g, SE3::Identity(), style.max_z_m))
      canvas.polygon(poly, height_fill(style, top), viz::colors::kGrey, 0.8);
}

}  // namespace

void draw_world(viz::Canvas& canvas, const World& world, double t_s, const WorldStyle& style) {
  draw_statics(canvas, world, style);
  for (const Actor& a : world.actors) {
    Polygon2 path;
    for (const Waypoint& w : a.trajectory) path.push_back(w.pose.translation().head<2>());
    if (a.loop && path.size() > 2) path.push_back(path.front());
    canvas.polyline(path, style.actor_path, 1.0);
    for (const Geometry& g : a.parts)
      for (const Polygon2& poly : footprint(g, a.pose_at(t_s), style.max_z_m))
        canvas.polygon(poly, style.actor_fill, style.actor_fill, 0.5);
  }
}

}  // namespace bipednav::sim
