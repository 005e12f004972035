// The stance-height level graph of DijkstraHeuristic (heuristics.hpp): its construction and
// queries.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <queue>
#include <vector>

#include "bipednav/planning/footstep/heuristics.hpp"
#include "bipednav/planning/footstep/octile.hpp"

namespace bipednav::footstep {

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
namespace {

// What the action set allows between levels (see the derivation above).
struct LevelSteps {
  int free_k = 0;          // level changes that cost nothing (planar, T-step, step-over)
  int jump_k = 0;          // the largest level change of any action
  int gap_k = 0;           // gaps between standable levels filled in (the flatness)
  double penalty_m = 0.0;  // the cost of a change of more than free_k levels
  double d_max_m = 0.0;    // the largest nominal body displacement
};

LevelSteps level_steps(const ActionSet& actions, double v_max, double res) {
  constexpr double kLevelM = DijkstraHeuristic::kLevelM;
  const double sep = actions.body.nominal_separation_m;
  double dz_free = 0.0, dz_all = 0.0;
  LevelSteps s;
  for (const auto& a : actions.actions) {
    const double dz = std::max(std::abs(a.dz_min_m), std::abs(a.dz_max_m));
    dz_all = std::max(dz_all, dz);
    s.d_max_m = std::max(s.d_max_m, body_centre_displacement_m(a, sep));
    if (a.kind == ActionKind::kPlanar || a.kind == ActionKind::kTStep || a.kind == ActionKind::kStepOver)
      dz_free = std::max(dz_free, dz);
  }
  double penalty = std::numeric_limits<double>::infinity();
  for (const auto& a : actions.actions) {
    const double dz = std::max(std::abs(a.dz_min_m), std::abs(a.dz_max_m));
    if (dz <= dz_free) continue;
    penalty = std::min(penalty, std::max(0.0, v_max * a.duration_s - body_centre_displacement_m(a, sep) - 2.0 * res));
  }
  s.free_k = static_cast<int>(std::floor(dz_free / kLevelM + 1e-9)) + 1;
  s.jump_k = std::isfinite(penalty) ? static_cast<int>(std::floor(dz_all / kLevelM + 1e-9)) + 1 : s.free_k;
  s.penalty_m = std::isfinite(penalty) ? penalty : 0.0;
  s.gap_k = static_cast<int>(std::floor(actions.flatness_threshold_m / kLevelM + 1e-9)) + 1;
  return s;
}

// Per-cell level bitsets: `words` 64-bit words per cell of `g`, levels 0 .. levels - 1.
struct LevelBitsets {
  const mapping::GridGeometry& g;
  int levels;
  std::size_t words;

  std::vector<std::uint64_t> zeros() const { return std::vector<std::uint64_t>(g.size() * words, 0); }
  void set_range(std::vector<std::uint64_t>& b, std::size_t cell, int l0, int l1) const {
    for (int l = std::max(0, l0); l <= std::min(levels - 1, l1); ++l)
      b[cell * words + static_cast<std::size_t>(l) / 64] |= std::uint64_t{1} << (l % 64);
  }
  // OR over the (2r + 1)^2 square around each cell, separably.
  std::vector<std::uint64_t> dilate(const std::vector<std::uint64_t>& in, int r) const {
    std::vector<std::uint64_t> tmp = zeros(), out = zeros();
    or_window(in, tmp, r, true);
    or_window(tmp, out, r, false);
    return out;
  }
  // out |= in over the 2r + 1 cells along x (along_x) or y around each cell.
  void or_window(const std::vector<std::uint64_t>& in, std::vector<std::uint64_t>& out, int r, bool along_x) const {
    const int n = along_x ? g.width : g.height;
    for (int y = 0; y < g.height; ++y)
      for (int x = 0; x < g.width; ++x) {
        std::uint64_t* o = &out[g.index(x, y) * words];
        const int c = along_x ? x : y;
        for (int i = std::max(0, c - r); i <= std::min(n - 1, c + r); ++i) {
          const std::uint64_t* s = &in[(along_x ? g.index(i, y) : g.index(x, i)) * words];
          for (std::size_t k = 0; k < words; ++k) o[k] |= s[k];
        }
      }
  }
};

// The 8-connected graph's passable edges, once per cell: bit k for the step (kOctileDx[k], kOctileDy[k]).
std::vector<std::uint8_t> passable_edges(const TerrainGrid& terrain, const ActionSet& actions) {
  const auto& g = terrain.geometry();
  std::vector<std::uint8_t> passable(g.size(), 0);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x)
      for (int k = 0; k < 8; ++k)
        if (g.in_bounds(x + kOctileDx[k], y + kOctileDy[k]) &&
            classify_edge(terrain, x, y, x + kOctileDx[k], y + kOctileDy[k], actions) != EdgeClass::kImpassable)
          passable[g.index(x, y)] |= static_cast<std::uint8_t>(1u << k);
  return passable;
}

}  // namespace

void DijkstraHeuristic::build_level_graph(const ActionSet& actions, const mapping::Cell& goal_cell) {
  const double res = terrain_->geometry().resolution_m;
  const LevelSteps steps = level_steps(actions, v_max_, res);
  level_penalty_m_ = steps.penalty_m;
  if (!build_stand_levels(actions, steps.gap_k)) return;
  // Every point of an action's segment lies within half its length of one end, at that end's level.
  const double r_half = (steps.d_max_m + 2.0 * res) / 2.0 + res * std::numbers::sqrt2;
  if (!build_allowed_levels(std::max(r_half, tolerance_m_ + res * std::numbers::sqrt2))) return;
  search_level_graph(actions, goal_cell, steps.free_k, steps.jump_k);
}

bool DijkstraHeuristic::build_stand_levels(const ActionSet& actions, int gap_k) {
  const auto& g = terrain_->geometry();
  const double res = g.resolution_m;
  const double flat = actions.flatness_threshold_m;
  const double sep = actions.body.nominal_separation_m;
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
  if (!std::isfinite(zlo)) return false;
  level_z0_ = zlo - kLevelM;
  levels_ = level_of(zhi) + 2;
  if (levels_ > 1024) return false;  // heights spread over more than 4 m: not worth it
  words_ = (levels_ + 63) / 64;
  const LevelBitsets bits{g, levels_, static_cast<std::size_t>(words_)};
  const std::size_t W = bits.words;
  std::vector<std::uint64_t> hbits = bits.zeros();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (terrain_->known(x, y) && sole_cell(x, y))
        bits.set_range(hbits, g.index(x, y), level_of(terrain_->min_h(x, y)), level_of(terrain_->max_h(x, y)));
  const BodyModel& b = actions.body;
  const double r_sole = sep / 2.0 + std::hypot(b.foot_length_m, b.foot_width_m) / 2.0 + 2.0 * res;
  const int n_sole = static_cast<int>(std::ceil(r_sole / res));
  stand_ = bits.dilate(hbits, n_sole);
  // The stance foot's own cell (a sole cell) lies within separation / 2 + res / sqrt(2) of C's
  // centre: z lies in [max_h(q) - flatness, min_h(q) + flatness] for one of those cells q.
  std::vector<std::uint64_t> qbits = bits.zeros();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (terrain_->known(x, y))
        bits.set_range(qbits, g.index(x, y), level_of(terrain_->max_h(x, y) - flat),
                       level_of(terrain_->min_h(x, y) + flat));
  const int n_ring = static_cast<int>(std::ceil((sep / 2.0 + res / std::numbers::sqrt2) / res + 1e-9));
  const std::vector<std::uint64_t> ring = bits.dilate(qbits, n_ring);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t c = g.index(x, y);
      if (!terrain_->range(x - n_sole, y - n_sole, x + n_sole, y + n_sole).all_known) {
        bits.set_range(stand_, c, 0, levels_ - 1);
        continue;
      }
      int prev = -1;
      for (int l = 0; l < levels_; ++l) {
        if (!bit(stand_, c, l)) continue;
        if (prev >= 0 && l - prev > 1 && l - prev <= gap_k) bits.set_range(stand_, c, prev + 1, l - 1);
        prev = l;
      }
      for (std::size_t k = 0; k < W; ++k) stand_[c * W + k] &= ring[c * W + k];
    }
  return true;
}

bool DijkstraHeuristic::build_allowed_levels(double reach_m) {
  const auto& g = terrain_->geometry();
  const LevelBitsets bits{g, levels_, static_cast<std::size_t>(words_)};
  const std::size_t n = g.size(), W = bits.words;
  allowed_ = bits.dilate(stand_, static_cast<int>(std::ceil(reach_m / g.resolution_m)));
  // Nodes: the allowed levels of each cell, in level order.
  node_begin_.assign(n + 1, 0);
  for (std::size_t c = 0; c < n; ++c) {
    std::uint32_t cnt = 0;
    for (std::size_t k = 0; k < W; ++k) cnt += static_cast<std::uint32_t>(std::popcount(allowed_[c * W + k]));
    node_begin_[c + 1] = node_begin_[c] + cnt;
  }
  // A safety valve for terrain with very many height levels close together.
  if (node_begin_[n] > 48 * n) {
    stand_.clear(), allowed_.clear(), node_begin_.clear();
    return false;
  }
  return true;
}

void DijkstraHeuristic::search_level_graph(const ActionSet& actions, const mapping::Cell& goal_cell, int free_k,
                                           int jump_k) {
  const auto& g = terrain_->geometry();
  const double res = g.resolution_m;
  const std::size_t n = g.size(), nodes = node_begin_[n];
  std::vector<std::uint32_t> node_cell(nodes);
  std::vector<std::uint16_t> node_level(nodes);
  for (std::size_t c = 0; c < n; ++c) {
    std::uint32_t i = node_begin_[c];
    for (int l = 0; l < levels_; ++l)
      if (bit(allowed_, c, l))
        node_cell[i] = static_cast<std::uint32_t>(c), node_level[i++] = static_cast<std::uint16_t>(l);
  }
  const std::vector<std::uint8_t> passable = passable_edges(*terrain_, actions);
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
      const std::size_t nc = g.index(cc.x + kOctileDx[k], cc.y + kOctileDy[k]);
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

}  // namespace bipednav::footstep
