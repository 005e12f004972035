#include "bipednav/planning/global/dstar_lite.hpp"

#include <algorithm>
#include <cmath>

namespace bipednav::planning::global {

Key DStarLite::calculate_key(std::size_t s, int x, int y) const {
  const Cost m = std::min(g_[s], rhs_[s]);
  if (m >= kInfCost) return {kInfCost, kInfCost};
  return {m + model_.octile(x - start_x_, y - start_y_) + km_, m};
}

void DStarLite::update_vertex(std::size_t u, int x, int y) {
  const bool inconsistent = g_[u] != rhs_[u];
  if (inconsistent)
    open_.push(u, calculate_key(u, x, y));
  else if (open_.contains(u))
    open_.remove(u);
}

Cost DStarLite::best_successor_value(std::size_t s) const {
  const int x = model_.x_of(s), y = model_.y_of(s);
  Cost best = kInfCost;
  for (int k = 0; k < kNumNeighbours; ++k) {
    const Cost c = model_.edge_cost(x, y, k);
    if (c >= kInfCost) continue;
    best = std::min(best, add_cost(c, g_[model_.idx(x + kDx[k], y + kDy[k])]));
  }
  return best;
}

void DStarLite::initialize(std::size_t start, std::size_t goal) {
  const std::size_t n = model_.size();
  g_.assign(n, kInfCost);
  rhs_.assign(n, kInfCost);
  if (open_.capacity() != n) open_.resize(n);
  open_.clear();
  stamp_.assign(n, 0);
  stamp_gen_ = 0;
  km_ = 0;
  start_ = last_ = start;
  start_x_ = model_.x_of(start);
  start_y_ = model_.y_of(start);
  goal_ = goal;
  rhs_[goal] = 0;
  open_.insert(goal, {model_.heuristic(start, goal), 0});
}

void DStarLite::move_start(std::size_t start) {
  if (start == start_) return;
  start_ = start;
  start_x_ = model_.x_of(start);
  start_y_ = model_.y_of(start);
  km_ += model_.heuristic(last_, start_);
  last_ = start_;
}

void DStarLite::expand_overconsistent(std::size_t u) {
  g_[u] = rhs_[u];
  open_.remove(u);
  const int x = model_.x_of(u), y = model_.y_of(u);
  for (int k = 0; k < kNumNeighbours; ++k) {
    const Cost c = model_.edge_cost(x, y, k);  // = c(s, u) by symmetry
    if (c >= kInfCost) continue;
    const std::size_t s = model_.idx(x + kDx[k], y + kDy[k]);
    if (s != goal_) rhs_[s] = std::min(rhs_[s], c + g_[u]);  // g(u) is finite here
    update_vertex(s, x + kDx[k], y + kDy[k]);
  }
}

void DStarLite::expand_underconsistent(std::size_t u) {
  const Cost g_old = g_[u];
  g_[u] = kInfCost;
  const int x = model_.x_of(u), y = model_.y_of(u);
  for (int k = 0; k < kNumNeighbours; ++k) {
    const Cost c = model_.edge_cost(x, y, k);
    if (c >= kInfCost) continue;
    const std::size_t s = model_.idx(x + kDx[k], y + kDy[k]);
    if (s != goal_ && rhs_[s] == add_cost(c, g_old)) rhs_[s] = best_successor_value(s);
    update_vertex(s, x + kDx[k], y + kDy[k]);
  }
  // u itself (the "∪ {u}" of line 27): its rhs does not depend on g(u), only its key changes.
  update_vertex(u, x, y);
}

SearchStatus DStarLite::compute_shortest_path(const Deadline& deadline, std::size_t& expansions) {
  std::size_t iterations = 0;
  while (!open_.empty() && (open_.top_key() < calculate_key(start_) || rhs_[start_] > g_[start_])) {
    if (++iterations % kDeadlineCheckEvery == 0 && deadline.expired()) return SearchStatus::kTimeout;
    const std::size_t u = open_.top();
    const Key k_old = open_.top_key();
    const Key k_new = calculate_key(u);
    if (k_old < k_new) {
      open_.update(u, k_new);
    } else if (g_[u] > rhs_[u]) {
      expand_overconsistent(u);
      ++expansions;
    } else {
      expand_underconsistent(u);
      ++expansions;
    }
  }
  return rhs_[start_] >= kInfCost ? SearchStatus::kNoPath : SearchStatus::kFound;
}

void DStarLite::collect_affected(std::size_t cell) {
  const int x = model_.x_of(cell), y = model_.y_of(cell);
  for (int k = -1; k < kNumNeighbours; ++k) {
    const int nx = x + (k < 0 ? 0 : kDx[k]), ny = y + (k < 0 ? 0 : kDy[k]);
    if (nx < 0 || ny < 0 || nx >= model_.width() || ny >= model_.height()) continue;
    const std::size_t v = model_.idx(nx, ny);
    if (stamp_[v] == stamp_gen_) continue;
    stamp_[v] = stamp_gen_;
    affected_.push_back(v);
  }
}

void DStarLite::update_cells(const std::vector<CellUpdate>& updates, std::int64_t exempt) {
  // A cell's cost enters the edges incident to it and the diagonals passing its corner; all of
  // them start at the cell or one of its 8 neighbours.
  if (++stamp_gen_ == 0) {
    std::fill(stamp_.begin(), stamp_.end(), 0);
    stamp_gen_ = 1;
  }
  affected_.clear();
  for (const auto& u : updates) collect_affected(u.index);
  if (exempt != model_.exempt()) {
    if (model_.exempt() >= 0) collect_affected(static_cast<std::size_t>(model_.exempt()));
    if (exempt >= 0) collect_affected(static_cast<std::size_t>(exempt));
  }
  old_costs_.resize(affected_.size() * kNumNeighbours);
  for (std::size_t j = 0; j < affected_.size(); ++j)
    for (int k = 0; k < kNumNeighbours; ++k)
      old_costs_[j * kNumNeighbours + k] = model_.edge_cost(model_.x_of(affected_[j]), model_.y_of(affected_[j]), k);

  for (const auto& u : updates) model_.set_cost(u.index, u.cost);
  model_.set_exempt(exempt);

  for (std::size_t j = 0; j < affected_.size(); ++j) {
    const std::size_t u = affected_[j];
    const int x = model_.x_of(u), y = model_.y_of(u);
    for (int k = 0; k < kNumNeighbours; ++k) {
      const Cost c_old = old_costs_[j * kNumNeighbours + k];
      const Cost c_new = model_.edge_cost(x, y, k);
      if (c_old == c_new || u == goal_) continue;
      const std::size_t v = model_.idx(x + kDx[k], y + kDy[k]);
      if (c_old > c_new)
        rhs_[u] = std::min(rhs_[u], add_cost(c_new, g_[v]));
      else if (rhs_[u] == add_cost(c_old, g_[v]))
        rhs_[u] = best_successor_value(u);
    }
    update_vertex(u);
  }
}

std::size_t DStarLite::invariant_violations() const {
  std::size_t bad = 0;
  for (std::size_t s = 0; s < g_.size(); ++s) {
    const Cost expect = s == goal_ ? 0 : best_successor_value(s);
    if (rhs_[s] != expect || (g_[s] != rhs_[s]) != open_.contains(s)) ++bad;
  }
  return bad;
}

SearchOutcome DStarLite::extract_path() const {
  SearchOutcome out;
  if (rhs_[start_] >= kInfCost) return out;
  Cost total = 0;
  std::size_t s = start_;
  out.cells.push_back(s);
  // A shortest path is at most one cell per vertex; anything longer means a cycle.
  for (std::size_t steps = 0; s != goal_; ++steps) {
    if (steps > model_.size()) return {};
    const int x = model_.x_of(s), y = model_.y_of(s);
    Cost best = kInfCost, best_c = kInfCost;
    std::size_t next = s;
    for (int k = 0; k < kNumNeighbours; ++k) {
      const Cost c = model_.edge_cost(x, y, k);
      if (c >= kInfCost) continue;
      const std::size_t v = model_.idx(x + kDx[k], y + kDy[k]);
      if (add_cost(c, g_[v]) < best) {
        best = add_cost(c, g_[v]);
        best_c = c;
        next = v;
      }
    }
    if (best >= kInfCost) return {};
    total += best_c;
    s = next;
    out.cells.push_back(s);
  }
  out.status = SearchStatus::kFound;
  out.cost = model_.to_metres(total);
  return out;
}

}  // namespace bipednav::planning::global
