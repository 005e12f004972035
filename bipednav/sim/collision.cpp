#include "bipednav/sim/collision.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::sim {

void CollisionParams::validate() const {
  require(ground_clearance_m >= 0 && std::isfinite(ground_clearance_m), "ground_clearance_m", ">= 0");
}

CollisionChecker::CollisionChecker(const World& world, double radius_m, double height_m, const CollisionParams& params)
    : radius_m_(radius_m), z_lo_(params.ground_clearance_m), z_hi_(height_m), actors_(world.actors) {
  params.validate();
  require(radius_m > 0 && std::isfinite(radius_m), "footprint_radius_m", "> 0");
  require(height_m > params.ground_clearance_m && std::isfinite(height_m), "height_m", "> ground_clearance_m");
  for (const Geometry& g : world.statics)
    for (Footprint2D& f : slab_footprints(g, SE3::Identity(), z_lo_, z_hi_)) statics_.push_back({std::move(f), g.name});
}

void CollisionChecker::consider(const Footprint2D& f, const std::string& name, const Eigen::Vector2d& c,
                                Proximity& best) const {
  // Bounding-box lower bound first: most footprints are far away.
  const Eigen::Vector2d gap = (f.bbox_min - c).cwiseMax(c - f.bbox_max).cwiseMax(0.0);
  if (gap.norm() - radius_m_ >= best.clearance_m) return;
  const double clearance = signed_distance(f, c) - radius_m_;
  if (clearance < best.clearance_m) {
    best.clearance_m = clearance;
    best.point = closest_point(f, c);
    best.obstacle = name;
  }
}

Proximity CollisionChecker::nearest(const Eigen::Vector2d& center, double t_s) const {
  if (!center.allFinite()) throw Error("CollisionChecker: non-finite robot position");
  Proximity best;
  for (const Named& s : statics_) consider(s.footprint, s.name, center, best);
  for (const Actor& a : actors_) {
    const SE3 T = a.pose_at(t_s);
    for (const Geometry& part : a.parts)
      for (const Footprint2D& f : slab_footprints(part, T, z_lo_, z_hi_))
        consider(f, a.name + "/" + part.name, center, best);
  }
  return best;
}

}  // namespace bipednav::sim
