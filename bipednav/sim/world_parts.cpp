#include "bipednav/sim/world_parts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "bipednav/common/error.hpp"
#include "bipednav/common/se3.hpp"

namespace bipednav::sim {
namespace {

constexpr double kProbeRadius_m = 1e-6;  // CollisionChecker measures from a disc; this one is a point

// Distance from p to the segment ab.
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Whether the segments ab and cd cross (proper or touching).
bool segments_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d) {
  const double d1 = cross2(b - a, c - a), d2 = cross2(b - a, d - a);
  const double d3 = cross2(d - c, a - c), d4 = cross2(d - c, b - c);
  return d1 * d2 <= 0.0 && d3 * d4 <= 0.0;
}

World statics_only(const World& world) {
  World w;
  w.name = world.name;
  w.statics = world.statics;
  return w;
}

}  // namespace

Geometry wall_segment(const std::string& name, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  return floor_box(name, 0.5 * (a + b), std::atan2(d.y(), d.x()),
                   Eigen::Vector3d(d.norm() + kWallThickness_m, kWallThickness_m, kWallHeight_m));
}

Geometry floor_box(const std::string& name, const Eigen::Vector2d& c, double yaw_rad, const Eigen::Vector3d& size_m) {
  return Geometry{name, make_se3(c.x(), c.y(), 0.5 * size_m.z(), 0, 0, yaw_rad), Box{size_m}};
}

Geometry pillar(const std::string& name, const Eigen::Vector2d& c, double radius_m, double height_m) {
  return Geometry{name, make_se3(c.x(), c.y(), 0.5 * height_m, 0, 0, 0), Cylinder{radius_m, height_m}};
}

std::vector<Geometry> table(const std::string& name, const Eigen::Vector2d& c, double yaw_rad,
                            const Eigen::Vector2d& size_m) {
  constexpr double kTop_m = 0.74, kTopThickness_m = 0.04, kLegRadius_m = 0.03, kLegInset_m = 0.06;
  std::vector<Geometry> parts;
  parts.push_back(Geometry{name + "::top", make_se3(c.x(), c.y(), kTop_m, 0, 0, yaw_rad),
                           Box{Eigen::Vector3d(size_m.x(), size_m.y(), kTopThickness_m)}});
  const Eigen::Rotation2Dd R(yaw_rad);
  const double leg_h = kTop_m - 0.5 * kTopThickness_m;
  int k = 0;
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0}) {
      const Eigen::Vector2d off(sx * (0.5 * size_m.x() - kLegInset_m), sy * (0.5 * size_m.y() - kLegInset_m));
      parts.push_back(pillar(name + "::leg_" + std::to_string(++k), c + R * off, kLegRadius_m, leg_h));
    }
  return parts;
}

Actor person(const std::string& name, double radius_m, const std::vector<Eigen::Vector2d>& loop, double speed_mps,
             double phase) {
  require(loop.size() >= 2, "person.loop", "at least two points");
  require(speed_mps > 0.0 && std::isfinite(speed_mps), "person.speed_mps", "> 0");
  const std::size_t n = loop.size();
  double length = 0.0;
  for (std::size_t i = 0; i < n; ++i) length += (loop[(i + 1) % n] - loop[i]).norm();
  require(length > 0.0, "person.loop", "of positive length");
  // Start at the phase: walk the loop from the point at phase * length, once round.
  double skip = std::clamp(phase, 0.0, 1.0) * length;
  std::size_t first = 0;
  while ((loop[(first + 1) % n] - loop[first]).norm() <= skip && first + 1 < n) {
    skip -= (loop[(first + 1) % n] - loop[first]).norm();
    ++first;
  }
  const Eigen::Vector2d seg = loop[(first + 1) % n] - loop[first];
  const Eigen::Vector2d p0 = loop[first] + (seg.norm() > 0.0 ? skip / seg.norm() : 0.0) * seg;
  std::vector<Eigen::Vector2d> pts{p0};
  for (std::size_t k = 1; k <= n; ++k) pts.push_back(loop[(first + k) % n]);
  pts.push_back(p0);
  Actor a;
  a.name = name;
  a.loop = true;
  a.parts.push_back(
      Geometry{"body", make_se3(0, 0, 0.5 * kPersonHeight_m, 0, 0, 0), Cylinder{radius_m, kPersonHeight_m}});
  double t = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (i > 0) t += (pts[i] - pts[i - 1]).norm() / speed_mps;
    // Facing the way it walks next (the last waypoint closes the loop, facing as the first).
    const Eigen::Vector2d dir = pts[i + 1 < pts.size() ? i + 1 : 1] - pts[i + 1 < pts.size() ? i : 0];
    const double yaw = dir.squaredNorm() > 0.0 ? std::atan2(dir.y(), dir.x()) : 0.0;
    if (i > 0 && (pts[i] - pts[i - 1]).squaredNorm() == 0.0) continue;  // a zero-length start segment
    a.trajectory.push_back(Waypoint{t, make_se3(pts[i].x(), pts[i].y(), 0, 0, 0, yaw)});
  }
  return a;
}

std::vector<Eigen::Vector2d> circle_loop(const Eigen::Vector2d& center, double radius_m, int n) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n;
    pts.push_back(center + radius_m * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  return pts;
}

double loop_to_polyline_distance(const std::vector<Eigen::Vector2d>& loop, const std::vector<Eigen::Vector2d>& line) {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d &a = loop[i], &b = loop[(i + 1) % n];
    if (line.size() == 1) best = std::min(best, segment_distance(line.front(), a, b));  // a point
    for (std::size_t j = 1; j < line.size(); ++j) {
      if (segments_cross(a, b, line[j - 1], line[j])) return 0.0;
      best = std::min({best, segment_distance(a, line[j - 1], line[j]), segment_distance(b, line[j - 1], line[j]),
                       segment_distance(line[j - 1], a, b), segment_distance(line[j], a, b)});
    }
  }
  return best;
}

StaticClearance::StaticClearance(const World& world, double height_m)
    : checker_(statics_only(world), kProbeRadius_m, height_m) {}

double StaticClearance::at(const Eigen::Vector2d& p) const { return checker_.clearance_m(p, 0.0) + kProbeRadius_m; }

double StaticClearance::along_loop(const std::vector<Eigen::Vector2d>& loop, double step_m) const {
  double best = std::numeric_limits<double>::infinity();
  const std::size_t n = loop.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d &a = loop[i], &b = loop[(i + 1) % n];
    const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step_m)));
    for (int k = 0; k < steps; ++k) best = std::min(best, at(a + (b - a) * (static_cast<double>(k) / steps)));
  }
  return best;
}

}  // namespace bipednav::sim
