#include "bipednav/planning/footstep/heuristics.hpp"

#include <algorithm>
#include <bit>
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

// The 8-connected neighbourhood (0..3 orthogonal, 4..7 diagonal).
constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};

// Octile steps scaled by the worst octile/Euclidean ratio (1.0824) keep a graph distance below
// the length of any continuous path. (A 16-connected graph, worst ratio 1.0275, was tried: its
// tighter distances changed nao_stairs' epsilon-3 plans in the loop into one that brushed the
// side wall with an arm; kept 8-connected.)
double octile_step_m(int k, double res) {
  constexpr double kOctileToEuclid = 1.0 / 1.0823922;
  return (k < 4 ? res : res * std::numbers::sqrt2) * kOctileToEuclid;
}

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
                                     double tolerance_m, bool stance_levels)
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
      const int nx = c.x + kDx[k], ny = c.y + kDy[k];
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
  if (stance_levels) build_level_graph(actions, *goal_cell);
}

// The (cell, stance-height level) graph. Levels are kLevelM wide: level(z) = floor((z - z0) / kLevelM).
// Why h(s) = max(dL(C, level(z)) - slack, |c - g|) - tol, over v_max, never exceeds the cost to go
// of a state s with body centre c in cell C and stance height z:
//  - Standable levels stand(C). A landed state (every state but the start) passed the flatness
//    check: its known sole cells' heights lie in [lo, hi] with hi - lo <= flatness, and z (their
//    mean of means) lies in [lo, hi] too; lo is the min_h of a sole cell, hi the max_h of one,
//    and every sole cell spans at most the flatness. Sole cells lie within r_sole = separation / 2
//    + the sole's half diagonal + 2 res of C's centre. So level(z) lies between two levels of
//    H = the levels [level(min_h(q)), level(max_h(q))] of the cells q within r_sole that span at
//    most the flatness, at most gap_k = floor(flatness / kLevelM) + 1 apart: H (over the
//    Chebyshev square, a superset of the disc) with the gaps of at most gap_k levels filled.
//    Also, the stance foot's own cell q0 is a sole cell within separation / 2 + res / sqrt(2) of
//    C's centre, so z lies in [max_h(q0) - flatness, min_h(q0) + flatness]: stand(C) is the first
//    set intersected with the union of those intervals over the cells that near (the "ring";
//    it keeps floor levels from reaching more than ~7 cm into a platform).
//    A sole with no known cell takes the previous stance height: when any in-bounds cell within
//    r_sole is unknown, stand(C) holds every level (off-map cells are skipped by the flatness
//    check like here). States out of the level range or at a level not standable in their cell
//    (the start) keep the 8-connected heuristic.
//  - The relaxed path of s_0 .. s_n (body centres c_i, heights z_i): action i moves along the
//    cells its segment c_i c_(i+1) crosses (the same passable edges and open cells as the
//    8-connected graph), at level(z_i) up to the cell of the segment's middle, where it changes
//    to level(z_(i+1)), and at that level on. Every point of the first half lies within half the
//    segment (at most (D_max + 2 res) / 2, D_max the largest nominal body displacement, 2 res the
//    lattice rounding of the landing) of c_i, every point of the second half as near c_(i+1), and
//    the level of each end is standable there. Hence a node (P, l) exists only within r_half =
//    (D_max + 2 res) / 2 + res sqrt(2) (Chebyshev) of a cell where l is standable (the last leg,
//    within tol of c_n, too). Level changes of planar, T-step and step-over actions (|dz| <=
//    dz_free) span at most free_k = floor(dz_free / kLevelM) + 1 levels (floors of two reals less
//    than m apart differ by at most floor(m) + 1) and cost nothing; a larger change needs an
//    action whose dz interval reaches beyond dz_free (step_onto/step_down), at most jump_k
//    levels, and costs level_penalty = min over those actions of v_max T - D - 2 res (one level
//    change per action, so T covers its segment, at most D + 2 res, plus the penalty).
//    The last state reaches the goal cell at level(z_n), a standable level of a cell within
//    tol + res / sqrt(2) of the goal: those levels are the sources at the goal cell.
//  Hence dL is no longer than the relaxed path's length plus the level penalties, and the
//  8-connected bound (which charges elevating edges instead) holds on its own: their maximum is
//  admissible. The level graph charges no elevating edges, so a step_onto counts once.
void DijkstraHeuristic::build_level_graph(const ActionSet& actions, const mapping::Cell& goal_cell) {
  const auto& g = terrain_->geometry();
  const double res = g.resolution_m;
  const double flat = actions.flatness_threshold_m;
  const double sep = actions.body.nominal_separation_m;
  const double v = v_max_;
  double dz_free = 0.0, dz_all = 0.0, d_max = 0.0;
  for (const auto& a : actions.actions) {
    const double dz = std::max(std::abs(a.dz_min_m), std::abs(a.dz_max_m));
    dz_all = std::max(dz_all, dz);
    d_max = std::max(d_max, body_centre_displacement_m(a, sep));
    if (a.kind == ActionKind::kPlanar || a.kind == ActionKind::kTStep || a.kind == ActionKind::kStepOver)
      dz_free = std::max(dz_free, dz);
  }
  double penalty = std::numeric_limits<double>::infinity();
  for (const auto& a : actions.actions) {
    const double dz = std::max(std::abs(a.dz_min_m), std::abs(a.dz_max_m));
    if (dz <= dz_free) continue;
    penalty = std::min(penalty, std::max(0.0, v * a.duration_s - body_centre_displacement_m(a, sep) - 2.0 * res));
  }
  const int free_k = static_cast<int>(std::floor(dz_free / kLevelM + 1e-9)) + 1;
  const int jump_k = std::isfinite(penalty) ? static_cast<int>(std::floor(dz_all / kLevelM + 1e-9)) + 1 : free_k;
  level_penalty_m_ = std::isfinite(penalty) ? penalty : 0.0;
  const int gap_k = static_cast<int>(std::floor(flat / kLevelM + 1e-9)) + 1;
  // Heights of the cells a sole can stand on.
  const int w = g.width, h = g.height;
  double zlo = std::numeric_limits<double>::infinity(), zhi = -zlo;
  const auto sole_cell = [&](int x, int y) { return terrain_->max_h(x, y) - terrain_->min_h(x, y) <= flat; };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (terrain_->known(x, y) && sole_cell(x, y)) {
        zlo = std::min(zlo, static_cast<double>(terrain_->min_h(x, y)));
        zhi = std::max(zhi, static_cast<double>(terrain_->max_h(x, y)));
      }
  if (!std::isfinite(zlo)) return;
  level_z0_ = zlo - kLevelM;
  levels_ = level_of(zhi) + 2;
  if (levels_ > 1024) return;  // heights spread over more than 4 m: not worth it
  words_ = (levels_ + 63) / 64;
  const std::size_t n = g.size(), W = static_cast<std::size_t>(words_);
  std::vector<std::uint64_t> hbits(n * W, 0);
  const auto set_range = [&](std::vector<std::uint64_t>& b, std::size_t cell, int l0, int l1) {
    for (int l = std::max(0, l0); l <= std::min(levels_ - 1, l1); ++l)
      b[cell * W + static_cast<std::size_t>(l) / 64] |= std::uint64_t{1} << (l % 64);
  };
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (terrain_->known(x, y) && sole_cell(x, y))
        set_range(hbits, g.index(x, y), level_of(terrain_->min_h(x, y)), level_of(terrain_->max_h(x, y)));
  // OR over the (2r + 1)^2 square around each cell, separably.
  const auto dilate = [&](const std::vector<std::uint64_t>& in, int r) {
    std::vector<std::uint64_t> tmp(n * W, 0), out(n * W, 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        std::uint64_t* t = &tmp[g.index(x, y) * W];
        for (int xx = std::max(0, x - r); xx <= std::min(w - 1, x + r); ++xx) {
          const std::uint64_t* s = &in[g.index(xx, y) * W];
          for (std::size_t k = 0; k < W; ++k) t[k] |= s[k];
        }
      }
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        std::uint64_t* o = &out[g.index(x, y) * W];
        for (int yy = std::max(0, y - r); yy <= std::min(h - 1, y + r); ++yy) {
          const std::uint64_t* s = &tmp[g.index(x, yy) * W];
          for (std::size_t k = 0; k < W; ++k) o[k] |= s[k];
        }
      }
    return out;
  };
  const BodyModel& b = actions.body;
  const double r_sole = sep / 2.0 + std::hypot(b.foot_length_m, b.foot_width_m) / 2.0 + 2.0 * res;
  const int n_sole = static_cast<int>(std::ceil(r_sole / res));
  stand_ = dilate(hbits, n_sole);
  // The stance foot's own cell (a sole cell) lies within separation / 2 + res / sqrt(2) of C's
  // centre: z lies in [max_h(q) - flatness, min_h(q) + flatness] for one of those cells q.
  std::vector<std::uint64_t> qbits(n * W, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (terrain_->known(x, y))
        set_range(qbits, g.index(x, y), level_of(terrain_->max_h(x, y) - flat), level_of(terrain_->min_h(x, y) + flat));
  const int n_ring = static_cast<int>(std::ceil((sep / 2.0 + res / std::numbers::sqrt2) / res + 1e-9));
  const std::vector<std::uint64_t> ring = dilate(qbits, n_ring);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t c = g.index(x, y);
      if (!terrain_->range(x - n_sole, y - n_sole, x + n_sole, y + n_sole).all_known) {
        set_range(stand_, c, 0, levels_ - 1);
        continue;
      }
      int prev = -1;
      for (int l = 0; l < levels_; ++l) {
        if (!bit(stand_, c, l)) continue;
        if (prev >= 0 && l - prev > 1 && l - prev <= gap_k) set_range(stand_, c, prev + 1, l - 1);
        prev = l;
      }
      for (std::size_t k = 0; k < W; ++k) stand_[c * W + k] &= ring[c * W + k];
    }
  // Every point of an action's segment lies within half its length of one end, at that end's level.
  const double r_half = (d_max + 2.0 * res) / 2.0 + res * std::numbers::sqrt2;
  allowed_ =
      dilate(stand_, static_cast<int>(std::ceil(std::max(r_half, tolerance_m_ + res * std::numbers::sqrt2) / res)));
  // Nodes: the allowed levels of each cell, in level order.
  node_begin_.assign(n + 1, 0);
  for (std::size_t c = 0; c < n; ++c) {
    std::uint32_t cnt = 0;
    for (std::size_t k = 0; k < W; ++k) cnt += static_cast<std::uint32_t>(std::popcount(allowed_[c * W + k]));
    node_begin_[c + 1] = node_begin_[c] + cnt;
  }
  const std::size_t nodes = node_begin_[n];
  // A safety valve for terrain with very many height levels close together.
  if (nodes > 48 * n) {
    stand_.clear(), allowed_.clear(), node_begin_.clear();
    return;
  }
  std::vector<std::uint32_t> node_cell(nodes);
  std::vector<std::uint16_t> node_level(nodes);
  for (std::size_t c = 0; c < n; ++c) {
    std::uint32_t i = node_begin_[c];
    for (int l = 0; l < levels_; ++l)
      if (bit(allowed_, c, l))
        node_cell[i] = static_cast<std::uint32_t>(c), node_level[i++] = static_cast<std::uint16_t>(l);
  }
  // The 8-connected graph's passable edges, once per cell.
  std::vector<std::uint8_t> passable(n, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < 8; ++k)
        if (g.in_bounds(x + kDx[k], y + kDy[k]) &&
            classify_edge(*terrain_, x, y, x + kDx[k], y + kDy[k], actions) != EdgeClass::kImpassable)
          passable[g.index(x, y)] |= static_cast<std::uint8_t>(1u << k);
  level_dist_.assign(nodes, std::numeric_limits<float>::infinity());
  using Item = std::pair<float, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  const std::size_t gc = g.index(goal_cell);
  // Sources: at the goal cell, the standable levels of the cells within tol + res / sqrt(2).
  const double keep_r = tolerance_m_ + res / std::numbers::sqrt2;
  const int nk = static_cast<int>(std::ceil(keep_r / res)) + 1;
  for (int dy = -nk; dy <= nk; ++dy)
    for (int dx = -nk; dx <= nk; ++dx) {
      const int x = goal_cell.x + dx, y = goal_cell.y + dy;
      if (!g.in_bounds(x, y)) continue;
      const auto p = g.cell_center(x, y);
      if (std::hypot(p.x() - goal_.x, p.y() - goal_.y) > keep_r) continue;
      for (int l = 0; l < levels_; ++l) {
        if (!bit(stand_, g.index(x, y), l) || !bit(allowed_, gc, l)) continue;
        const std::uint32_t i = node_index(gc, l);
        if (level_dist_[i] == 0.0f) continue;
        level_dist_[i] = 0.0f;
        open.push({0.0f, i});
      }
    }
  const float pen = static_cast<float>(level_penalty_m_);
  while (!open.empty()) {
    const auto [d, i] = open.top();
    open.pop();
    if (d > level_dist_[i]) continue;
    const std::size_t c = node_cell[i];
    const int l = node_level[i];
    if (c != gc && !blocked_.empty() && blocked_[c]) continue;  // reached, not passed on
    const mapping::Cell cc = g.cell_of(c);
    const auto relax = [&](std::uint32_t j, float nd) {
      if (nd < level_dist_[j]) {
        level_dist_[j] = nd;
        open.push({nd, j});
      }
    };
    for (int k = 0; k < 8; ++k) {
      if (!((passable[c] >> k) & 1u)) continue;
      const std::size_t nc = g.index(cc.x + kDx[k], cc.y + kDy[k]);
      if (!bit(allowed_, nc, l)) continue;
      relax(node_index(nc, l), static_cast<float>(d + octile_step_m(k, res)));
    }
    // A level change (at the middle of an action's segment): the nodes of this cell are
    // consecutive, in level order.
    for (std::uint32_t j = node_begin_[c]; j < node_begin_[c + 1]; ++j) {
      const int l2 = node_level[j];
      if (l2 == l || std::abs(l2 - l) > jump_k) continue;
      relax(j, std::abs(l2 - l) <= free_k ? d : d + pen);
    }
  }
}

std::optional<double> DijkstraHeuristic::level_distance_m(int x, int y, double stance_z) const {
  if (level_dist_.empty() || !terrain_->in_bounds(x, y) || !std::isfinite(stance_z)) return std::nullopt;
  const int l = level_of(stance_z);
  if (l < 0 || l >= levels_) return std::nullopt;
  const std::size_t c = terrain_->geometry().index(x, y);
  if (!bit(stand_, c, l)) return std::nullopt;
  return static_cast<double>(level_dist_[node_index(c, l)]);
}

std::uint32_t DijkstraHeuristic::node_index(std::size_t c, int l) const {
  // The nodes of cell c are its allowed levels in level order: l's rank among them.
  const std::size_t W = static_cast<std::size_t>(words_), wl = static_cast<std::size_t>(l) / 64;
  std::uint32_t r = node_begin_[c];
  for (std::size_t k = 0; k < wl; ++k) r += static_cast<std::uint32_t>(std::popcount(allowed_[c * W + k]));
  const std::uint64_t below = (std::uint64_t{1} << (l % 64)) - 1;
  return r + static_cast<std::uint32_t>(std::popcount(allowed_[c * W + wl] & below));
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

double DijkstraHeuristic::seconds_to_goal_at(double x, double y, double stance_z) const {
  const double base = seconds_to_goal(x, y);
  if (level_dist_.empty()) return base;
  const auto c = terrain_->geometry().world_to_cell(x, y);
  if (!c) return base;
  const double straight = std::hypot(x - goal_.x, y - goal_.y);
  if (straight <= tolerance_m_) return base;
  const auto d = level_distance_m(c->x, c->y, stance_z);
  if (!d) return base;  // not a standable level here (the start state): the 8-connected bound
  if (!std::isfinite(*d)) return std::numeric_limits<double>::infinity();
  const double slack = terrain_->geometry().resolution_m * std::numbers::sqrt2;
  return std::max(base, std::max(0.0, std::max(*d - slack, straight) - tolerance_m_) / v_max_);
}

}  // namespace bipednav::footstep
