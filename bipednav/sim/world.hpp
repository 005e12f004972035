#pragma once

#include <Eigen/Core>
#include <string>
#include <variant>
#include <vector>

#include "bipednav/common/se3.hpp"

namespace bipednav::sim {

// Shapes in their own frame, following SDF conventions: a box and a cylinder (axis z) are
// centred on their frame's origin; a plane passes through the origin with the given normal.
struct Box {
  Eigen::Vector3d size_m{1, 1, 1};
};
struct Cylinder {
  double radius_m = 0.5;
  double length_m = 1.0;
};
struct Sphere {
  double radius_m = 0.5;
};
struct Plane {
  Eigen::Vector3d normal{0, 0, 1};
  Eigen::Vector2d size_m{0, 0};  // 0 = unbounded
};
struct Mesh {
  std::vector<Eigen::Vector3f> vertices;
  std::vector<Eigen::Vector3i> triangles;
};
using Shape = std::variant<Box, Cylinder, Sphere, Plane, Mesh>;

// One collision/visual body: a shape placed in its parent frame (the world, or an actor).
struct Geometry {
  std::string name;
  SE3 T_parent_shape = SE3::Identity();
  Shape shape;
};

// A key pose of an actor's scripted trajectory.
struct Waypoint {
  double time_s = 0.0;
  SE3 pose = SE3::Identity();
};

// A moving obstacle following a scripted trajectory (SDF <actor><script>): piecewise-linear
// interpolation between waypoints, optionally looping, starting after `delay_s`.
struct Actor {
  std::string name;
  std::vector<Geometry> parts;  // in the actor's frame
  std::vector<Waypoint> trajectory;
  bool loop = true;
  double delay_s = 0.0;

  SE3 pose_at(double t_s) const {
    if (trajectory.empty()) return SE3::Identity();
    if (trajectory.size() == 1 || t_s <= delay_s) return trajectory.front().pose;
    const double t0 = trajectory.front().time_s, t1 = trajectory.back().time_s;
    double t = t0 + (t_s - delay_s);
    if (t1 > t0) {
      if (loop)
        t = t0 + std::fmod(t - t0, t1 - t0);
      else if (t >= t1)
        return trajectory.back().pose;
    }
    for (std::size_t i = 1; i < trajectory.size(); ++i) {
      if (t <= trajectory[i].time_s) {
        const Waypoint& a = trajectory[i - 1];
        const Waypoint& b = trajectory[i];
        const double span = b.time_s - a.time_s;
        return se3_interpolate(a.pose, b.pose, span > 0 ? (t - a.time_s) / span : 1.0);
      }
    }
    return trajectory.back().pose;
  }
};

// Everything a simulated sensor can hit. Static geometry is in the world frame.
struct World {
  std::string name;
  std::vector<Geometry> statics;
  std::vector<Actor> actors;
};

}  // namespace bipednav::sim
