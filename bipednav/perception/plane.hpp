#pragma once

#include <Eigen/Core>
#include <cmath>

namespace bipednav::perception {

// A plane a x + b y + c z + d = 0 (eq. 4.1) stored as [a, b, c, d] with a unit normal (a, b, c)
// and, by convention, c >= 0 so that "above the plane" means a positive signed distance when the
// plane is the ground seen from a z-up frame.
using Plane = Eigen::Vector4d;

// The prior ground: z = 0 of the frame (base_link on the ground, REP-105).
inline Plane ground_plane_z0() { return Plane(0.0, 0.0, 1.0, 0.0); }

// Scales to a unit normal and flips so that c >= 0 (if c == 0: b >= 0, then a >= 0).
inline Plane normalize_plane(const Plane& p) {
  const double n = p.head<3>().norm();
  if (!(n > 0.0)) return p;
  Plane q = p / n;
  const bool flip = q[2] < 0.0 || (q[2] == 0.0 && (q[1] < 0.0 || (q[1] == 0.0 && q[0] < 0.0)));
  return flip ? Plane(-q) : q;
}

// Signed distance of p to a plane with unit normal (eq. 4.2 without the absolute value).
inline float signed_distance(const Eigen::Vector4f& plane, const Eigen::Vector3f& p) {
  return plane[0] * p.x() + plane[1] * p.y() + plane[2] * p.z() + plane[3];
}

}  // namespace bipednav::perception
