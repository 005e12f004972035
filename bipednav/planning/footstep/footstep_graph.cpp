#include "bipednav/planning/footstep/footstep_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>

namespace bipednav::planning::footstep {

ActionLattice::ActionLattice(const ActionSet& actions, double res, int theta_bins, double landing_margin_m)
    : actions_(actions), res_(res), bins_(theta_bins), margin_m_(landing_margin_m) {
  actions_.validate();
  require(res > 0.0, "lattice_resolution_m", "> 0");
  require(theta_bins >= 4, "theta_bins", ">= 4");
  require(std::isfinite(landing_margin_m) && landing_margin_m >= 0.0 && landing_margin_m <= 0.1, "landing_margin_m",
          "in [0, 0.1] m");
  const std::size_t n = 2 * actions_.actions.size() * static_cast<std::size_t>(bins_);
  trans_.resize(n);
  ihm_.resize(n);
  for (Foot f : {Foot::kLeft, Foot::kRight}) {
    const double m = f == Foot::kLeft ? 1.0 : -1.0;
    for (std::size_t a = 0; a < actions_.actions.size(); ++a) {
      const FootstepAction& act = actions_.actions[a];
      for (int t = 0; t < bins_; ++t) {
        const double th = theta_of(t), c = std::cos(th), s = std::sin(th);
        const double dx = act.dx_m, dy = m * act.dy_m;
        Transition& tr = trans_[slot(f, static_cast<int>(a), t)];
        tr.dix = static_cast<int>(std::lround((c * dx - s * dy) / res));
        tr.diy = static_cast<int>(std::lround((s * dx + c * dy) / res));
        tr.ditheta = static_cast<int>(std::lround(m * act.dtheta_rad / (2.0 * std::numbers::pi / bins_)));
        ihm_[slot(f, static_cast<int>(a), t)] = build_inverse_heightmap(act, actions_.body, f, th, res);
      }
    }
  }
  soles_.resize(bins_);
  rings_.resize(bins_);
  for (int t = 0; t < bins_; ++t) {
    soles_[t] = footprint_cells(actions_.body, theta_of(t), res);
    for (const auto& [dx, dy] : soles_[t]) sole_radius_ = std::max({sole_radius_, std::abs(dx), std::abs(dy)});
    if (margin_m_ <= 0.0) continue;
    const auto sole = soles_[t];
    for (const auto& c : footprint_cells(actions_.body, theta_of(t), res, margin_m_)) {
      if (std::find(sole.begin(), sole.end(), c) != sole.end()) continue;
      rings_[t].push_back(c);
      ring_radius_ =
          std::max({ring_radius_, std::abs(static_cast<int>(c.first)), std::abs(static_cast<int>(c.second))});
    }
  }
}

double ActionLattice::theta_of(int itheta) const { return normalize_angle(itheta * 2.0 * std::numbers::pi / bins_); }

int ActionLattice::bin_of(double theta) const {
  const int b = static_cast<int>(std::lround(theta / (2.0 * std::numbers::pi / bins_)));
  return ((b % bins_) + bins_) % bins_;
}

FootstepGraph::FootstepGraph(const ActionLattice& lattice, const TerrainGrid& terrain, const Heuristic& heuristic,
                             const FootstepGoal& goal, const Footstep& start, double start_swing_lift_m)
    : lattice_(lattice),
      terrain_(terrain),
      heuristic_(heuristic),
      goal_(goal),
      start_lift_m_(std::isfinite(start_swing_lift_m) && start_swing_lift_m > kMinSwingLiftM ? start_swing_lift_m
                                                                                             : 0.0) {
  cell_block_.assign(terrain.geometry().size(), -1);
  const int bins = lattice.theta_bins();
  const double half = lattice.actions().body.nominal_separation_m / 2.0;
  centre_dx_.resize(2 * static_cast<std::size_t>(bins));
  centre_dy_.resize(centre_dx_.size());
  centre_theta_.resize(centre_dx_.size());
  for (int t = 0; t < bins; ++t) {
    for (Foot f : {Foot::kLeft, Foot::kRight}) {
      // The body centre lies half a separation towards the other (swing) foot: Pose2's
      // composition with (0, oy, 0), whose terms in 0 add nothing.
      const double th = lattice.theta_of(t), oy = f == Foot::kLeft ? -half : half;
      const std::size_t i = 2 * static_cast<std::size_t>(t) + static_cast<std::size_t>(f);
      centre_dx_[i] = std::sin(th) * oy;
      centre_dy_[i] = std::cos(th) * oy;
      centre_theta_[i] = normalize_angle(th + 0.0);
    }
  }
  const auto cell = terrain.geometry().world_to_cell_unbounded(start.pose.x, start.pose.y);
  const StateKey k{cell ? cell->x : 0, cell ? cell->y : 0, lattice.bin_of(start.pose.theta), start.foot};
  start_ = intern(k, static_cast<float>(start.z_m));
  const auto& actions = lattice.actions().actions;
  min_duration_s_ = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < actions.size(); ++a) {
    min_duration_s_ = std::min(min_duration_s_, actions[a].duration_s);
    for (Foot f : {Foot::kLeft, Foot::kRight})
      max_turn_bins_ = std::max(max_turn_bins_, std::abs(lattice.transition(f, static_cast<int>(a), 0).ditheta));
  }
}

FootstepGraph::StateIndex::StateIndex() : slots_(std::size_t{1} << 12), shift_(64 - 12) {}

std::int32_t FootstepGraph::StateIndex::find_or_insert(std::uint64_t key, std::int32_t fresh_id, bool* fresh) {
  // The packed key never reaches 2^64 - 1 (its top bits are 20-bit coordinates), so key + 1 > 0.
  const std::uint64_t stored = key + 1;
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t i = home(key);; i = (i + 1) & mask) {
    Slot& s = slots_[i];
    if (s.key_plus_one == stored) {
      *fresh = false;
      return s.id;
    }
    if (s.key_plus_one == 0) {
      s = {stored, fresh_id};
      *fresh = true;
      if (2 * ++used_ > slots_.size()) grow();  // load factor at most 1/2
      return fresh_id;
    }
  }
}

void FootstepGraph::StateIndex::grow() {
  std::vector<Slot> old(slots_.size() * 2);
  old.swap(slots_);
  --shift_;
  const std::size_t mask = slots_.size() - 1;
  for (const Slot& s : old) {
    if (s.key_plus_one == 0) continue;
    std::size_t i = home(s.key_plus_one - 1);
    while (slots_[i].key_plus_one != 0) i = (i + 1) & mask;
    slots_[i] = s;
  }
}

std::size_t FootstepGraph::block_of(int ix, int iy) {
  std::int32_t& b = cell_block_[terrain_.geometry().index(ix, iy)];
  if (b < 0) {
    const std::size_t bins = static_cast<std::size_t>(lattice_.theta_bins());
    constexpr std::size_t kChunk = std::size_t{1} << kChunkShift;
    if ((blocks_ & (kChunk - 1)) == 0) {
      id_chunks_.emplace_back(new std::int32_t[kChunk * 2 * bins]);
      std::fill_n(id_chunks_.back().get(), kChunk * 2 * bins, -1);
      landing_chunks_.emplace_back(new LandingCache[kChunk * bins]);
    }
    b = static_cast<std::int32_t>(blocks_++);
  }
  return static_cast<std::size_t>(b);
}

std::int32_t* FootstepGraph::block_ids(std::size_t b) {
  const std::size_t in_chunk = b & ((std::size_t{1} << kChunkShift) - 1);
  return id_chunks_[b >> kChunkShift].get() + in_chunk * 2 * static_cast<std::size_t>(lattice_.theta_bins());
}

FootstepGraph::LandingCache* FootstepGraph::block_landings(std::size_t b) {
  const std::size_t in_chunk = b & ((std::size_t{1} << kChunkShift) - 1);
  return landing_chunks_[b >> kChunkShift].get() + in_chunk * static_cast<std::size_t>(lattice_.theta_bins());
}

std::int32_t FootstepGraph::intern(const StateKey& k, float z) {
  const auto fresh_id = static_cast<std::int32_t>(states_.size());
  if (terrain_.in_bounds(k.ix, k.iy)) {
    std::int32_t& id =
        block_ids(block_of(k.ix, k.iy))[2 * static_cast<std::size_t>(k.itheta) + static_cast<std::size_t>(k.stance)];
    if (id >= 0) return id;
    id = fresh_id;
    states_.push_back({k, z});
    return fresh_id;
  }
  bool fresh = false;
  const std::int32_t id = index_.find_or_insert(k.packed(), fresh_id, &fresh);
  if (fresh) states_.push_back({k, z});
  return id;
}

Pose2 FootstepGraph::pose_of(const StateKey& k) const {
  const auto c = terrain_.geometry().cell_center(k.ix, k.iy);
  return {c.x(), c.y(), lattice_.theta_of(k.itheta)};
}

Footstep FootstepGraph::footstep(std::int32_t s) const {
  return {pose_of(states_[s].key), states_[s].z, states_[s].key.stance};
}

Pose2 FootstepGraph::body_centre(std::int32_t s) const {
  const StateKey& k = states_[s].key;
  const auto c = terrain_.geometry().cell_center(k.ix, k.iy);
  const std::size_t i = 2 * static_cast<std::size_t>(k.itheta) + static_cast<std::size_t>(k.stance);
  return {c.x() - centre_dx_[i], c.y() + centre_dy_[i], centre_theta_[i]};
}

bool FootstepGraph::clear_of_rising_edges(int ix, int iy, int itheta, float top) const {
  const auto& ring = lattice_.margin_ring(itheta);
  if (ring.empty()) return true;
  const float limit = top + static_cast<float>(lattice_.actions().flatness_threshold_m);
  const int r = lattice_.ring_radius_cells();
  if (terrain_.range(ix - r, iy - r, ix + r, iy + r).max_h <= limit) return true;
  for (const auto& [dx, dy] : ring) {
    const int x = ix + dx, y = iy + dy;
    if (terrain_.in_bounds(x, y) && terrain_.known(x, y) && terrain_.max_h(x, y) > limit) return false;
  }
  return true;
}

FootstepGraph::Landing FootstepGraph::landing_at(int ix, int iy, int itheta, float* z) const {
  const int r = lattice_.sole_radius_cells();
  const auto quick = terrain_.range(ix - r, iy - r, ix + r, iy + r);
  if (quick.all_known && quick.max_h == quick.min_h) {  // uniformly flat: the mean is that height
    *z = quick.max_h;
    return clear_of_rising_edges(ix, iy, itheta, quick.max_h) ? Landing::kAt : Landing::kUnsafe;
  }
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  double sum = 0.0;
  int known = 0;
  for (const auto& [dx, dy] : lattice_.sole(itheta)) {
    const int x = ix + dx, y = iy + dy;
    if (!terrain_.in_bounds(x, y) || !terrain_.known(x, y)) continue;
    lo = std::min(lo, terrain_.min_h(x, y));
    hi = std::max(hi, terrain_.max_h(x, y));
    sum += terrain_.mean_h(x, y);
    ++known;
  }
  if (known == 0) return Landing::kStanceHeight;  // unknown ground is free: it continues the stance height
  *z = static_cast<float>(sum / known);
  return hi - lo <= lattice_.actions().flatness_threshold_m && clear_of_rising_edges(ix, iy, itheta, hi)
             ? Landing::kAt
             : Landing::kUnsafe;
}

bool FootstepGraph::landing_height(int ix, int iy, int itheta, float stance_z, float* z) {
  LandingCache& c = block_landings(block_of(ix, iy))[itheta];
  if (c.kind == Landing::kUnasked) c.kind = landing_at(ix, iy, itheta, &c.z);
  *z = c.kind == Landing::kStanceHeight ? stance_z : c.z;
  return c.kind != Landing::kUnsafe;
}

const InverseHeightmap& FootstepGraph::start_ihm(int a) {
  const StateKey& k = states_[start_].key;
  if (start_ihm_.empty()) {
    start_ihm_.resize(lattice_.actions().actions.size());
    start_ihm_built_.assign(start_ihm_.size(), false);
  }
  if (!start_ihm_built_[a]) {
    start_ihm_[a] = build_inverse_heightmap(lattice_.actions().actions[a], lattice_.actions().body, k.stance,
                                            lattice_.theta_of(k.itheta), lattice_.resolution_m(), start_lift_m_, true);
    start_ihm_built_[a] = true;
  }
  return start_ihm_[a];
}

bool FootstepGraph::whole_body_free(const StateKey& s, float z, const InverseHeightmap& ihm) const {
  // Eq. 5: every IHM cell must stay above the terrain once aligned at the stance height.
  // The body band (torso, arms) must also keep off occluded cells (TerrainGrid::occluded): the
  // walker meets the true wall behind a face the map holds only the lower part of.
  const float body_band = static_cast<float>(lattice_.actions().body.torso_bottom_m) - 1e-4f;
  for (const IhmLayer& layer : ihm.layers) {
    const int x0 = s.ix + layer.min_dx, y0 = s.iy + layer.min_dy, x1 = s.ix + layer.max_dx, y1 = s.iy + layer.max_dy;
    const auto quick = terrain_.range(x0, y0, x1, y1);
    const bool occlusion = layer.min_height_m >= body_band && terrain_.any_occluded(x0, y0, x1, y1);
    if (quick.max_h < layer.min_height_m + z && !occlusion) continue;
    for (const IhmCell& c : layer.cells) {
      const int x = s.ix + c.dx, y = s.iy + c.dy;
      if (!terrain_.in_bounds(x, y)) continue;
      if (!terrain_.known(x, y)) {
        if (occlusion && terrain_.occluded(x, y)) return false;
        continue;
      }
      if (!(c.min_height_m + z > terrain_.max_h(x, y))) return false;
    }
  }
  return true;
}

bool FootstepGraph::action_safe(std::int32_t s, int a, std::int32_t* to) {
  const State st = states_[s];
  const FootstepAction& act = lattice_.actions().actions[a];
  const auto& tr = lattice_.transition(st.key.stance, a, st.key.itheta);
  const int bins = lattice_.theta_bins();
  const StateKey nk{st.key.ix + tr.dix, st.key.iy + tr.diy, ((st.key.itheta + tr.ditheta) % bins + bins) % bins,
                    other(st.key.stance)};
  if (!terrain_.in_bounds(nk.ix, nk.iy)) return false;
  float z = 0.0f;
  if (!landing_height(nk.ix, nk.iy, nk.itheta, st.z, &z)) return false;
  const double dz = z - st.z;  // eq. 4
  if (dz < act.dz_min_m || dz > act.dz_max_m) return false;
  // The start's inverse heightmap has no cell lower than the lattice's (its swing foot is
  // lifted, its lift-off sweeps fewer cells): it is built and checked only when that one fails.
  if (!whole_body_free(st.key, st.z, lattice_.ihm(st.key.stance, a, st.key.itheta)) &&
      (s != start_ || !whole_body_free(st.key, st.z, start_ihm(a))))
    return false;
  if (to) *to = intern(nk, z);
  return true;
}

void FootstepGraph::successors(std::int32_t s, std::vector<Edge>& out) {
  const auto& actions = lattice_.actions().actions;
  for (std::size_t a = 0; a < actions.size(); ++a) {
    std::int32_t to = -1;
    if (action_safe(s, static_cast<int>(a), &to))
      out.push_back({to, static_cast<std::int32_t>(a), actions[a].duration_s});
  }
}

double FootstepGraph::heuristic(std::int32_t s) {
  const Pose2 c = body_centre(s);
  const double h = heuristic_.seconds_to_goal(c.x, c.y);
  if (max_turn_bins_ == 0) return h;
  // Each action turns the (discrete) heading by at most max_turn_bins_ bins, so reaching the
  // goal's heading tolerance takes at least this many actions.
  const double turn = std::abs(angle_diff(lattice_.theta_of(states_[s].key.itheta), goal_.body.theta));
  const double need = turn - goal_.tolerance_rad;
  if (need <= 0.0) return h;
  const double per_action = max_turn_bins_ * 2.0 * std::numbers::pi / lattice_.theta_bins();
  return std::max(h, std::ceil(need / per_action - 1e-9) * min_duration_s_);
}

bool FootstepGraph::is_goal(std::int32_t s) {
  std::int8_t& goal = states_[s].goal;
  if (goal < 0) {
    const Pose2 c = body_centre(s);
    goal = std::hypot(c.x - goal_.body.x, c.y - goal_.body.y) <= goal_.tolerance_m &&
           std::abs(angle_diff(c.theta, goal_.body.theta)) <= goal_.tolerance_rad;
  }
  return goal != 0;
}

}  // namespace bipednav::planning::footstep
