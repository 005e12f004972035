#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/sim/footprint2d.hpp"
#include "bipednav/sim/world.hpp"

namespace bipednav::sim {

struct CollisionParams {
  // Obstacles are what the footprint cylinder meets in z in [ground_clearance_m, height]:
  // the floor (and anything lower than this) is not an obstacle.
  double ground_clearance_m = 0.02;

  void validate() const;
};

// The nearest obstacle to the robot's footprint.
struct Proximity {
  double clearance_m = std::numeric_limits<double>::infinity();  // footprint edge to obstacle; < 0 = penetration
  Eigen::Vector2d point{0, 0};                                   // nearest obstacle point (on its footprint boundary)
  std::string obstacle;                                          // geometry name ("actor_name/part_name" for actors)
};

// Robot footprint = vertical cylinder (radius, height) standing on z = 0, checked against the
// world's static geometry (footprints precomputed) and actors (at their pose at time t).
// Exact for boxes, vertical cylinders and spheres; meshes per triangle (a robot entirely inside
// a closed mesh without touching a triangle in the slab is not detected; it cannot get there
// without touching one first).
class CollisionChecker {
 public:
  CollisionChecker(const World& world, double radius_m, double height_m, const CollisionParams& params = {});

  Proximity nearest(const Eigen::Vector2d& center, double t_s) const;
  double clearance_m(const Eigen::Vector2d& center, double t_s) const { return nearest(center, t_s).clearance_m; }
  bool in_collision(const Eigen::Vector2d& center, double t_s) const { return clearance_m(center, t_s) < 0.0; }

  std::size_t static_footprint_count() const { return statics_.size(); }

 private:
  struct Named {
    Footprint2D footprint;
    std::string name;
  };
  void consider(const Footprint2D& f, const std::string& name, const Eigen::Vector2d& c, Proximity& best) const;

  double radius_m_, z_lo_, z_hi_;
  std::vector<Named> statics_;
  std::vector<Actor> actors_;
};

}  // namespace bipednav::sim
