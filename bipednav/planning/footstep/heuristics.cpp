#include "bipednav/planning/footstep/heuristics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <queue>

namespace bipednav::footstep {

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

DijkstraHeuristic::DijkstraHeuristic(const TerrainGrid& terrain, const ActionSet& actions, const Pose2& goal,
                                     double tolerance_m)
    : terrain_(&terrain), goal_(goal), tolerance_m_(tolerance_m), v_max_(actions.fastest_speed_mps()) {
  const auto& g = terrain.geometry();
  elevation_penalty_m_ = elevation_penalty(actions);
  dist_.assign(g.size(), std::numeric_limits<float>::infinity());
  const auto goal_cell = g.world_to_cell(goal.x, goal.y);
  if (!goal_cell) return;
  using Item = std::pair<float, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist_[g.index(*goal_cell)] = 0.0f;
  open.push({0.0f, static_cast<std::uint32_t>(g.index(*goal_cell))});
  // Octile steps scaled by the worst octile/Euclidean ratio (1.0824) keep d(s) below the length
  // of any continuous path.
  constexpr double kOctileToEuclid = 1.0 / 1.0823922;
  const double res = g.resolution_m;
  constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
  constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  while (!open.empty()) {
    const auto [d, i] = open.top();
    open.pop();
    if (d > dist_[i]) continue;
    const mapping::Cell c = g.cell_of(i);
    for (int k = 0; k < 8; ++k) {
      const int nx = c.x + kDx[k], ny = c.y + kDy[k];
      if (!g.in_bounds(nx, ny)) continue;
      const EdgeClass e = classify_edge(terrain, c.x, c.y, nx, ny, actions);
      if (e == EdgeClass::kImpassable) continue;
      double step = (k < 4 ? res : res * std::numbers::sqrt2) * kOctileToEuclid;
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

}  // namespace bipednav::footstep
