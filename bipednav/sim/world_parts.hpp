#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "bipednav/sim/collision.hpp"
#include "bipednav/sim/world.hpp"

// Building blocks of the generated worlds (world_generator.hpp): walls, furniture and people, and
// the geometric checks the generator draws them against.
namespace bipednav::sim {

inline constexpr double kWallThickness_m = 0.1;
inline constexpr double kWallHeight_m = 2.0;
inline constexpr double kPersonHeight_m = 1.7;

// A wall from a to b (its centre line), kWallThickness_m thick and kWallHeight_m high.
Geometry wall_segment(const std::string& name, const Eigen::Vector2d& a, const Eigen::Vector2d& b);
// A box standing on the floor, centred on c, turned by yaw.
Geometry floor_box(const std::string& name, const Eigen::Vector2d& c, double yaw_rad, const Eigen::Vector3d& size_m);
// A vertical cylinder standing on the floor.
Geometry pillar(const std::string& name, const Eigen::Vector2d& c, double radius_m, double height_m);
// A table: a 0.04 m top at 0.72-0.76 m on four 0.03 m-radius legs, its parts named name::top, name::leg_k.
std::vector<Geometry> table(const std::string& name, const Eigen::Vector2d& c, double yaw_rad,
                            const Eigen::Vector2d& size_m);

// A person: an actor whose body is a vertical cylinder of the given radius and kPersonHeight_m,
// walking the closed polyline `loop` (its last point joins its first) at speed_mps, starting
// at the fraction `phase` of the loop's length. A back-and-forth walk is the loop a, b, a.
Actor person(const std::string& name, double radius_m, const std::vector<Eigen::Vector2d>& loop, double speed_mps,
             double phase);

// The back-and-forth walk a -> b -> a as a loop.
inline std::vector<Eigen::Vector2d> back_and_forth(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return {a, b};
}
// A regular polygon with n corners approximating a circle.
std::vector<Eigen::Vector2d> circle_loop(const Eigen::Vector2d& center, double radius_m, int n = 12);

// Smallest distance between a closed loop and an open polyline (0 when they cross); a polyline of
// one point is that point.
double loop_to_polyline_distance(const std::vector<Eigen::Vector2d>& loop, const std::vector<Eigen::Vector2d>& line);

// The clearance of a disc walking along a closed loop from the world's static geometry (the
// smallest over points spaced step_m along it; negative: it overlaps something).
class StaticClearance {
 public:
  StaticClearance(const World& world, double height_m);
  double at(const Eigen::Vector2d& p) const;
  double along_loop(const std::vector<Eigen::Vector2d>& loop, double step_m = 0.05) const;

 private:
  CollisionChecker checker_;
};

}  // namespace bipednav::sim
