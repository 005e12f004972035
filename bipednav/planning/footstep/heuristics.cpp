#include "bipednav/planning/footstep/heuristics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <queue>

#include "bipednav/planning/footstep/octile.hpp"

namespace bipednav::planning::footstep {

EuclideanHeuristic::EuclideanHeuristic(const Pose2& goal, double tolerance_m, double v_max_mps)
    : goal_(goal), tolerance_m_(tolerance_m), v_max_(v_max_mps) {}

double EuclideanHeuristic::seconds_to_goal(double x, double y) const {
  return std::max(0.0, std::hypot(x - goal_.x, y - goal_.y) - tolerance_m_) / v_max_;
}

namespace {

double swing_peak_planar(const ActionSet& a) {
  double peak = std::numeric_limits<double>::infinity();
  for (const auto& act : a.actions)
    if (act.kind == ActionKind::kPlanar) peak = std::min(peak, act.peak_m);
  return std::isfinite(peak) ? peak : a.flatness_threshold_m;
}

// The least extra distance-equivalent a 3D action costs beyond a planar step covering the same
// body displacement, halved because one action may cross two elevation edges (up and down a bar).
double elevation_penalty(const ActionSet& a) {
  const double v = a.fastest_speed_mps();
  double penalty = std::numeric_limits<double>::infinity();
  for (const auto& act : a.actions) {
    if (act.kind == ActionKind::kPlanar || act.kind == ActionKind::kTStep) continue;
    const double extra = v * act.duration_s - body_centre_displacement_m(act, a.body.nominal_separation_m);
    penalty = std::min(penalty, std::max(0.0, extra) / 2.0);
  }
  return std::isfinite(penalty) ? penalty : 0.0;
}

}  // namespace

EdgeClass classify_edge(const TerrainGrid& t, int x0, int y0, int x1, int y1, const ActionSet& actions) {
  const bool k0 = t.known(x0, y0), k1 = t.known(x1, y1);
  if (!k0 && !k1) return EdgeClass::kPlanar;  // unknown ground is free (the footstep graph's view)
  if (!k0 || !k1) {
    // Unknown cells count as the floor (0), but an unseen tread may hide in them: a known cell
    // up to two steps above the floor is reachable through them (elevating). As a plain step, a
    // 10 cm platform whose lower stair was not seen yet was a cliff, and the heuristic infinite
    // for every state behind it; walls stay impassable.
    const double h = std::abs(k0 ? t.max_h(x0, y0) : t.max_h(x1, y1));
    if (h > 2.0 * actions.max_step_height_m) return EdgeClass::kImpassable;
    return h < swing_peak_planar(actions) ? EdgeClass::kPlanar : EdgeClass::kElevating;
  }
  const double dh = std::abs(t.max_h(x0, y0) - t.max_h(x1, y1));
  if (dh > actions.max_step_height_m) return EdgeClass::kImpassable;
  // A planar swing foot clears bumps lower than its peak without any 3D action.
  if (dh < swing_peak_planar(actions)) return EdgeClass::kPlanar;
  return EdgeClass::kElevating;
}

// Why h(s) = max(d(C) - slack, |c - g|) - tol, over v_max, never exceeds the cost to go (c the
// body centre of s, C its cell, g the goal, d the distance below):
//  - every action moves the body centre by at most v_max times its duration (v_max is the
//    largest such ratio), and the 3D actions cost at least the elevation penalty more per
//    elevating edge their body centre crosses (elevation_penalty);
//  - d(C) is no longer than the body-centre polyline c = c_0, c_1, ..., c_n (c_n within tol of
//    g) plus the slack for c and g sitting off their cell centres, because (i) the straight
//    segments between consecutive body centres cross only cells joined by passable edges
//    (the point-robot model of section V-D2, assumed as before, not proven: a body centre never
//    passes a step steeper than the robot's maximum step, nor a closed cell between two
//    states), and the 8-connected cell path through the cells a segment
//    crosses is at most 1.0824 (octile) times longer than it; (ii) no body centre c_i with
//    i < n lies in a cell closed by body clearance: each such state takes an action, and every
//    action's whole-body check fails there (mark_body_blocked). The start state's cell may be
//    closed (its stance sole was never checked): closed cells still receive a distance from
//    their open neighbours, they only do not pass it on. The last state c_n is exempt: cells
//    within the goal tolerance are never closed.
DijkstraHeuristic::DijkstraHeuristic(const TerrainGrid& terrain, const ActionSet& actions, const Pose2& goal,
                                     double tolerance_m)
    : terrain_(&terrain), goal_(goal), tolerance_m_(tolerance_m), v_max_(actions.fastest_speed_mps()) {
  const auto& g = terrain.geometry();
  elevation_penalty_m_ = elevation_penalty(actions);
  dist_.assign(g.size(), std::numeric_limits<float>::infinity());
  const auto goal_cell = g.world_to_cell(goal.x, goal.y);
  if (!goal_cell) return;
  mark_body_blocked(actions);
  using Item = std::pair<float, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist_[g.index(*goal_cell)] = 0.0f;
  open.push({0.0f, static_cast<std::uint32_t>(g.index(*goal_cell))});
  const double res = g.resolution_m;
  while (!open.empty()) {
    const auto [d, i] = open.top();
    open.pop();
    if (d > dist_[i]) continue;
    const mapping::Cell c = g.cell_of(i);
    if (body_blocked(c.x, c.y) && !(c.x == goal_cell->x && c.y == goal_cell->y)) continue;  // reached, not passed on
    for (int k = 0; k < 8; ++k) {
      const int nx = c.x + kOctileDx[k], ny = c.y + kOctileDy[k];
      if (!g.in_bounds(nx, ny)) continue;
      const EdgeClass e = classify_edge(terrain, c.x, c.y, nx, ny, actions);
      if (e == EdgeClass::kImpassable) continue;
      double step = octile_step_m(k, res);
      if (e == EdgeClass::kElevating) step += elevation_penalty_m_;
      const float nd = static_cast<float>(d + step);
      const std::size_t ni = g.index(nx, ny);
      if (nd < dist_[ni]) {
        dist_[ni] = nd;
        open.push({nd, static_cast<std::uint32_t>(ni)});
      }
    }
  }
}

// Body clearance. Every action's inverse heightmap holds the torso at the first instant of the
// action (inverse_heightmap.cpp: add_body with the swing foot at its via point), a box of
// torso_depth x torso_width centred on the body centre c, at torso_bottom above the stance
// sole, and the whole-body check fails on any known cell under it (centre within the box grown
// by half a cell) with max_h >= z + torso_bottom (z: the stance height; the torso's cells
// are compared even on the soles). The box contains the
// disc of radius min(depth, width) / 2 around c in every orientation, and c lies within half a
// cell diagonal of its cell centre C: a known cell p with |p - C| <= rho = min(depth, width) / 2
// - res / sqrt(2) is always under the torso.
// The stance height is bounded from the terrain near C: the stance sole (checked flat when the
// state was landed: its known cells' heights lie within flatness_threshold of z) reaches to
// (separation - foot width) / 2 from c on its side, so it holds the lattice cell nearest to the
// point 0.75 res further out, whose centre lies within r_near = (separation - foot width) / 2 +
// 0.75 res + 2 res / sqrt(2) of C. Hence z <= Zc(C) = max over cells q within r_near of C of
// min_h(q) + flatness_threshold (infinite when any of them is unknown or off the map).
// A cell C with a known cell p within rho and max_h(p) > Zc(C) + torso_bottom is closed: no
// state whose body centre lies in C can take any action (a tall obstacle under the torso).
void DijkstraHeuristic::mark_body_blocked(const ActionSet& actions) {
  const auto& g = terrain_->geometry();
  const BodyModel& b = actions.body;
  const double res = g.resolution_m;
  const double rho = std::min(b.torso_depth_m, b.torso_width_m) / 2.0 - res / std::numbers::sqrt2;
  const double r_near =
      std::max(0.0, (b.nominal_separation_m - b.foot_width_m) / 2.0) + 0.75 * res + 2.0 * res / std::numbers::sqrt2;
  // The nearest stance-sole cell argument needs soles of a cell and a half at least.
  if (rho <= 0.0 || std::min(b.foot_width_m, b.foot_length_m) < 1.5 * res) return;
  clearance_radius_m_ = rho;
  const auto offsets = [&](double r, bool inclusive_outward) {
    std::vector<std::pair<int, int>> out;
    const int n = static_cast<int>(std::ceil(r / res)) + 1;
    for (int dy = -n; dy <= n; ++dy)
      for (int dx = -n; dx <= n; ++dx) {
        const double d = std::hypot(dx, dy) * res;
        // Zc may take more cells (a larger bound), the torso disc must not.
        if (inclusive_outward ? d <= r + 1e-9 : d <= r - 1e-9) out.emplace_back(dx, dy);
      }
    return out;
  };
  const auto near = offsets(r_near, true), torso = offsets(rho, false);
  const float flat = static_cast<float>(actions.flatness_threshold_m);
  const float torso_bottom = static_cast<float>(b.torso_bottom_m);
  const double keep_r = tolerance_m_ + res / std::numbers::sqrt2;
  int reach = 0;
  for (const auto& [dx, dy] : torso) reach = std::max({reach, std::abs(dx), std::abs(dy)});
  const int w = g.width, h = g.height;
  blocked_.assign(g.size(), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // Zc(C) >= min_h(C) + flatness (C is among its own near cells): on open ground the
      // tallest cell in the disc's bounding square (a sparse-table lookup) settles it.
      if (!terrain_->known(x, y)) continue;
      const float floor_bound = terrain_->min_h(x, y) + flat + torso_bottom + 1e-4f;
      if (terrain_->range(x - reach, y - reach, x + reach, y + reach).max_h <= floor_bound) continue;
      float tallest = -std::numeric_limits<float>::infinity();
      for (const auto& [dx, dy] : torso) {
        const int px = x + dx, py = y + dy;
        if (terrain_->in_bounds(px, py) && terrain_->known(px, py))
          tallest = std::max(tallest, terrain_->max_h(px, py));
      }
      if (!std::isfinite(tallest)) continue;
      float zc = -std::numeric_limits<float>::infinity();
      for (const auto& [dx, dy] : near) {
        const int qx = x + dx, qy = y + dy;
        if (!terrain_->in_bounds(qx, qy) || !terrain_->known(qx, qy)) {
          zc = std::numeric_limits<float>::infinity();
          break;
        }
        zc = std::max(zc, terrain_->min_h(qx, qy) + flat);
      }
      // A margin above float rounding (the check compares z + 0.2f with max_h in floats).
      if (!(tallest > zc + torso_bottom + 1e-4f)) continue;
      const auto p = g.cell_center(x, y);
      if (std::hypot(p.x() - goal_.x, p.y() - goal_.y) <= keep_r) continue;  // the goal state's cell
      blocked_[g.index(x, y)] = 1;
    }
  }
}

double DijkstraHeuristic::seconds_to_goal(double x, double y) const {
  const auto& g = terrain_->geometry();
  const auto c = g.world_to_cell(x, y);
  // Off the lattice: fall back to the straight line, which is always admissible.
  if (!c) return std::max(0.0, std::hypot(x - goal_.x, y - goal_.y) - tolerance_m_) / v_max_;
  const double d = dist_[g.index(*c)];
  if (!std::isfinite(d)) return std::numeric_limits<double>::infinity();
  // The body centre and the goal may each sit half a cell diagonal from their cell centres.
  const double slack = g.resolution_m * std::numbers::sqrt2;
  // The octile scaling that keeps d(s) admissible everywhere makes it up to 7.6 % shorter than
  // the straight line in the open; the straight line is a lower bound too, so take the larger.
  const double straight = std::hypot(x - goal_.x, y - goal_.y);
  return std::max(0.0, std::max(d - slack, straight) - tolerance_m_) / v_max_;
}

}  // namespace bipednav::planning::footstep
