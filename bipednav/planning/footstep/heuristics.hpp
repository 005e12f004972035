#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/planning/footstep/action_set.hpp"
#include "bipednav/planning/footstep/terrain_grid.hpp"

namespace bipednav::footstep {

// Remaining travel time estimates h(s) = d(s) / v_max (eq. 6), evaluated at the body centre.
class Heuristic {
 public:
  virtual ~Heuristic() = default;
  virtual double seconds_to_goal(double body_x, double body_y) const = 0;
  // The same for a state whose stance sole stands at height z (stance-height-aware heuristics
  // override it; the default ignores z).
  virtual double seconds_to_goal_at(double body_x, double body_y, double /*stance_z*/) const {
    return seconds_to_goal(body_x, body_y);
  }
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
// With the stance height known (seconds_to_goal_at), it also takes the larger of that and a
// second Dijkstra over (cell, stance-height level) nodes: a state can only stand at the heights
// of flat ground within a sole's reach of its body centre, planar actions change the height by
// at most their dz, and a larger change costs a step_onto/step_down's extra time. A 3-4 cm
// platform, flat ground for the 8-connected graph, then costs the step down from it.
class DijkstraHeuristic : public Heuristic {
 public:
  // `stance_levels`: also build the (cell, level) graph (seconds_to_goal_at uses it). Off by
  // default: on Table I it made the 5 s suboptimality worse (FootstepPlannerParams).
  DijkstraHeuristic(const TerrainGrid& terrain, const ActionSet& actions, const Pose2& goal, double tolerance_m,
                    bool stance_levels = false);
  double seconds_to_goal(double x, double y) const override;
  double seconds_to_goal_at(double x, double y, double stance_z) const override;
  // The (cell, level) graph's distance for a state standing at z with its body centre in cell
  // (x, y); nullopt when the graph was not built or z is no standable level there (then
  // seconds_to_goal_at falls back to the 8-connected distance).
  std::optional<double> level_distance_m(int x, int y, double stance_z) const;
  bool has_level_graph() const { return !level_dist_.empty(); }
  std::size_t level_nodes() const { return level_dist_.size(); }
  double level_change_penalty_m() const { return level_penalty_m_; }
  static constexpr double kLevelM = 0.004;  // stance-height level width
  double distance_m(int x, int y) const { return dist_[terrain_->geometry().index(x, y)]; }
  double elevation_penalty_m() const { return elevation_penalty_m_; }
  // Whether no state can have its body centre in cell (x, y) and take an action (body clearance).
  bool body_blocked(int x, int y) const { return !blocked_.empty() && blocked_[terrain_->geometry().index(x, y)] != 0; }
  // The radius around a body centre within which a solid obstacle taller than the robot's feet
  // can clear closes the cell (0 when the body model leaves no such radius, e.g. Digit's wide stance).
  double clearance_radius_m() const { return clearance_radius_m_; }

 private:
  void mark_body_blocked(const ActionSet& actions);
  // The level graph (heuristic_levels.cpp): standable levels per cell, the levels a relaxed path
  // may take within reach_m of them and their node numbering (false when there is nothing to
  // build or too much), then the search from the goal.
  void build_level_graph(const ActionSet& actions, const mapping::Cell& goal_cell);
  bool build_stand_levels(const ActionSet& actions, int gap_k);
  bool build_allowed_levels(double reach_m);
  void search_level_graph(const ActionSet& actions, const mapping::Cell& goal_cell, int free_k, int jump_k);
  // The level bitsets: `words_` 64-bit words per cell, level 0 at z = level_z0_.
  int level_of(double z) const { return static_cast<int>(std::floor((z - level_z0_) / kLevelM)); }
  // The index of node (cell, level l); l must be an allowed level of the cell.
  std::uint32_t node_index(std::size_t cell, int l) const;
  bool bit(const std::vector<std::uint64_t>& b, std::size_t cell, int l) const {
    return (b[cell * words_ + static_cast<std::size_t>(l) / 64] >> (l % 64)) & 1u;
  }

  const TerrainGrid* terrain_;
  Pose2 goal_;
  double tolerance_m_, v_max_, elevation_penalty_m_ = 0.0, clearance_radius_m_ = 0.0;
  std::vector<float> dist_;
  std::vector<std::uint8_t> blocked_;
  // (cell, level) graph: standable levels per cell, nodes (allowed levels) per cell in
  // level order from node_begin_[cell], their distances.
  int levels_ = 0, words_ = 0;
  double level_z0_ = 0.0, level_penalty_m_ = 0.0;
  std::vector<std::uint64_t> stand_, allowed_;
  std::vector<std::uint32_t> node_begin_;
  std::vector<float> level_dist_;
};

// Edge class between two neighbouring lattice cells (for the heuristic and its figure).
enum class EdgeClass { kPlanar, kElevating, kImpassable };
EdgeClass classify_edge(const TerrainGrid& t, int x0, int y0, int x1, int y1, const ActionSet& actions);

}  // namespace bipednav::footstep
