#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/planning/footstep/action_set.hpp"
#include "bipednav/planning/footstep/terrain_grid.hpp"

namespace bipednav::planning::footstep {

// Remaining travel time estimates h(s) = d(s) / v_max (eq. 6), evaluated at the body centre.
class Heuristic {
 public:
  virtual ~Heuristic() = default;
  virtual double seconds_to_goal(double body_x, double body_y) const = 0;
};

// Straight-line distance to the goal (section V-D1).
class EuclideanHeuristic : public Heuristic {
 public:
  EuclideanHeuristic(const Pose2& goal, double tolerance_m, double v_max_mps);
  double seconds_to_goal(double x, double y) const override;

 private:
  Pose2 goal_;
  double tolerance_m_, v_max_;
};

// Dijkstra distances from the goal over an 8-connected graph of the lattice whose edges are
// planar (free), elevating (a step up/down/over: longer) or impassable (steeper than the
// robot's maximum step), section V-D2, and whose cells are closed to the body centre where a
// tall obstacle would stand under the torso (body clearance, heuristics.cpp). Octile distances
// are scaled down by the worst-case octile/Euclidean ratio and elevating edges only add what
// the fastest 3D action must cost over a planar one, so the heuristic stays admissible (the
// argument is in heuristics.cpp).
class DijkstraHeuristic : public Heuristic {
 public:
  DijkstraHeuristic(const TerrainGrid& terrain, const ActionSet& actions, const Pose2& goal, double tolerance_m);
  double seconds_to_goal(double x, double y) const override;
  double distance_m(int x, int y) const { return dist_[terrain_->geometry().index(x, y)]; }
  // Whether no state can have its body centre in cell (x, y) and take an action (body clearance).
  bool body_blocked(int x, int y) const { return !blocked_.empty() && blocked_[terrain_->geometry().index(x, y)] != 0; }
  // The radius around a body centre within which a solid obstacle taller than the robot's feet
  // can clear closes the cell (0 when the body model leaves no such radius, e.g. Digit's wide stance).
  double clearance_radius_m() const { return clearance_radius_m_; }

 private:
  void mark_body_blocked(const ActionSet& actions);

  const TerrainGrid* terrain_;
  Pose2 goal_;
  double tolerance_m_, v_max_, elevation_penalty_m_ = 0.0, clearance_radius_m_ = 0.0;
  std::vector<float> dist_;
  std::vector<std::uint8_t> blocked_;
};

// Edge class between two neighbouring lattice cells (for the heuristic and its figure).
enum class EdgeClass { kPlanar, kElevating, kImpassable };
EdgeClass classify_edge(const TerrainGrid& t, int x0, int y0, int x1, int y1, const ActionSet& actions);

}  // namespace bipednav::planning::footstep
