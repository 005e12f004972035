#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/planning/global/grid_cost_model.hpp"
#include "bipednav/planning/global/indexed_heap.hpp"
#include "bipednav/planning/global/search_types.hpp"

namespace bipednav::planning::global {

// A cell whose cost changes to `cost`.
struct CellUpdate {
  std::size_t index = 0;
  std::uint8_t cost = 0;
};

// The optimized D* Lite of Koenig & Likhachev (reference Algorithms 2-4) on the 8-connected grid
// of a GridCostModel. It searches from the goal towards the start, so the start may move between
// searches; changed cells repair the search incrementally. Edge costs are symmetric, so
// Pred(s) = Succ(s) and c(s, s') = c(s', s). All per-vertex state lives in flat arrays.
class DStarLite {
 public:
  explicit DStarLite(const GridCostParams& params = {}) : model_(params) {}

  // The map snapshot the search runs on; assign it before initialize().
  GridCostModel& model() { return model_; }
  const GridCostModel& model() const { return model_; }

  // Algorithm 2: g = rhs = inf everywhere, rhs(goal) = 0, U = {goal}, km = 0.
  void initialize(std::size_t start, std::size_t goal);
  // The robot moved: km += h(s_last, s_start), s_last = s_start (Algorithm 4, lines 12-13).
  void move_start(std::size_t start);
  // Applies changed cells (and a new start exemption, -1 for none) to the snapshot and updates
  // the rhs of every vertex with a changed outgoing edge (Algorithm 4, lines 14-23).
  void update_cells(const std::vector<CellUpdate>& updates, std::int64_t exempt);
  // Algorithm 3. On timeout the state stays valid and a later call resumes the search.
  SearchStatus compute_shortest_path(const Deadline& deadline, std::size_t& expansions);
  // Follows the successor minimising c(s, s') + g(s') from the start to the goal.
  SearchOutcome extract_path() const;

  bool initialized() const { return !g_.empty(); }
  std::size_t start() const { return start_; }
  std::size_t goal() const { return goal_; }
  Cost g(std::size_t s) const { return g_[s]; }
  Cost rhs(std::size_t s) const { return rhs_[s]; }
  // Vertices breaking the invariants (rhs(s) = min over s' of c(s, s') + g(s') for s != goal, and
  // s is queued exactly when g(s) != rhs(s)); O(n), for tests.
  std::size_t invariant_violations() const;

 private:
  Key calculate_key(std::size_t s, int x, int y) const;  // eqs. 5.2-5.3; (x, y) = cell of s
  Key calculate_key(std::size_t s) const { return calculate_key(s, model_.x_of(s), model_.y_of(s)); }
  void update_vertex(std::size_t u, int x, int y);
  void update_vertex(std::size_t u) { update_vertex(u, model_.x_of(u), model_.y_of(u)); }
  Cost best_successor_value(std::size_t s) const;  // min over s' of c(s, s') + g(s')
  void expand_overconsistent(std::size_t u);
  void expand_underconsistent(std::size_t u);
  void collect_affected(std::size_t cell);

  GridCostModel model_;
  std::vector<Cost> g_;
  std::vector<Cost> rhs_;
  IndexedHeap open_;
  Cost km_ = 0;
  std::size_t start_ = 0;
  int start_x_ = 0, start_y_ = 0;
  std::size_t last_ = 0;
  std::size_t goal_ = 0;
  // Scratch for update_cells: affected vertices (deduplicated by stamp) and their old edge costs.
  std::vector<std::uint32_t> stamp_;
  std::uint32_t stamp_gen_ = 0;
  std::vector<std::size_t> affected_;
  std::vector<Cost> old_costs_;
};

}  // namespace bipednav::planning::global
