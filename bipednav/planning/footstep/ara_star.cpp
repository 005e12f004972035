#include "bipednav/planning/footstep/ara_star.hpp"

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"

namespace bipednav::planning::footstep {

const char* search_clock_name(SearchClockKind k) { return k == SearchClockKind::kThreadCpu ? "thread_cpu" : "wall"; }

SearchClock::SearchClock(SearchClockKind kind) : kind_(kind), start_s_(0.0) { start_s_ = now_s(); }

double SearchClock::now_s() const {
  if (kind_ == SearchClockKind::kThreadCpu) {
    timespec ts{};
    if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) == 0)
      return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void AraStarParams::validate() const {
  require(initial_epsilon >= 1.0, "initial_epsilon", ">= 1");
  require(target_epsilon >= 1.0 && target_epsilon <= initial_epsilon, "target_epsilon", "in [1, initial_epsilon]");
  require(epsilon_decrease > 0.0 && epsilon_decrease < 1.0, "epsilon_decrease", "in (0, 1)");
  require(time_limit_s >= 0.0, "time_limit_s", ">= 0 (0 = no limit)");
  require(max_expansions > 0, "max_expansions", "> 0");
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// 32 bytes, so two share a cache line: the search's memory traffic is mostly these records.
struct Record {
  double g = kInf;
  double h = 0.0;
  std::int32_t parent = -1;
  std::int32_t heap_pos = -1;
  std::uint32_t closed_in = 0;  // search iteration that closed it (0 = open/never)
  std::int16_t action = -1;
  bool incons = false;
};
static_assert(sizeof(Record) == 32);

// Binary min-heap of state ids keyed by f = g + eps * h, with position tracking for updates.
// Key and id sit side by side, so a sift touches one array.
class OpenList {
 public:
  explicit OpenList(std::vector<Record>& rec) : rec_(rec) {}
  bool empty() const { return heap_.empty(); }
  double min_key() const { return heap_.empty() ? kInf : heap_[0].key; }
  void push_or_update(std::int32_t s, double key) {
    Record& r = rec_[s];
    if (r.heap_pos < 0) {
      r.heap_pos = static_cast<std::int32_t>(heap_.size());
      heap_.push_back({key, s});
      sift_up(static_cast<std::size_t>(r.heap_pos));  // a new leaf has no children
      return;
    }
    const std::size_t i = static_cast<std::size_t>(r.heap_pos);
    const bool lower = key <= heap_[i].key;
    heap_[i].key = key;
    // A key that did not rise is still no larger than its children's.
    if (sift_up(i) || lower) return;
    sift_down(i);
  }
  std::int32_t pop() {
    const std::int32_t top = heap_[0].id;
    rec_[top].heap_pos = -1;
    heap_[0] = heap_.back();
    heap_.pop_back();
    if (!heap_.empty()) {
      rec_[heap_[0].id].heap_pos = 0;
      sift_down(0);
    }
    return top;
  }
  std::vector<std::int32_t> drain() {
    std::vector<std::int32_t> all;
    all.reserve(heap_.size());
    for (const Entry& e : heap_) {
      all.push_back(e.id);
      rec_[e.id].heap_pos = -1;
    }
    heap_.clear();
    return all;
  }

 private:
  struct Entry {
    double key;
    std::int32_t id;
  };
  // The same moves as swapping the entry with its parent/child each step, with one write of
  // the moving entry at the end.
  bool sift_up(std::size_t i) {
    const Entry e = heap_[i];
    const std::size_t from = i;
    while (i > 0 && heap_[(i - 1) / 2].key > e.key) {
      place(i, heap_[(i - 1) / 2]);
      i = (i - 1) / 2;
    }
    place(i, e);
    return i != from;
  }
  void sift_down(std::size_t i) {
    const Entry e = heap_[i];
    const std::size_t n = heap_.size();
    for (;;) {
      const std::size_t l = 2 * i + 1, r = l + 1;
      std::size_t m = i;
      double mk = e.key;
      if (l < n && heap_[l].key < mk) {
        m = l;
        mk = heap_[l].key;
      }
      if (r < n && heap_[r].key < mk) m = r;
      if (m == i) break;
      place(i, heap_[m]);
      i = m;
    }
    place(i, e);
  }
  void place(std::size_t i, const Entry& e) {
    heap_[i] = e;
    rec_[e.id].heap_pos = static_cast<std::int32_t>(i);
  }

  std::vector<Record>& rec_;
  std::vector<Entry> heap_;
};

class Search {
 public:
  Search(SearchGraph& graph, const AraStarParams& p) : graph_(graph), p_(p), open_(rec_), clock_(p.clock) {}

  AraStarResult run() {
    AraStarResult out;
    double eps = p_.initial_epsilon;
    const std::int32_t start = graph_.start_state();
    touch(start);
    rec_[start].g = 0.0;
    open_.push_or_update(start, eps * rec_[start].h);
    double proven_bound = kInf;  // the epsilon of the last completed iteration
    for (std::uint32_t iteration = 1;; ++iteration) {
      const bool complete = improve_path(eps, iteration, out);
      if (complete) proven_bound = eps;
      // A solution improved by an interrupted iteration is still valid, with the last proven bound.
      if (goal_ >= 0 && (complete || !out.found || goal_g() < out.cost - 1e-9)) publish(proven_bound, out);
      if (!complete || eps <= p_.target_epsilon) break;
      eps = 1.0 + (eps - 1.0) * p_.epsilon_decrease;
      if (eps < 1.02) eps = 1.0;  // the last steps above 1 buy little
      eps = std::max(eps, p_.target_epsilon);
      reopen(eps);
    }
    out.expansions = expansions_;
    out.time_s = clock_.elapsed_s();
    return out;
  }

 private:
  void touch(std::int32_t s) {
    if (s >= static_cast<std::int32_t>(rec_.size())) {
      const std::size_t old = rec_.size();
      rec_.resize(static_cast<std::size_t>(s) + 1);
      for (std::size_t i = old; i < rec_.size(); ++i) rec_[i].h = -1.0;
    }
    if (rec_[s].h < 0.0) rec_[s].h = graph_.heuristic(s);
  }
  double key(std::int32_t s, double eps) const { return rec_[s].g + eps * rec_[s].h; }
  double goal_g() const { return goal_ >= 0 ? rec_[goal_].g : kInf; }

  // Expands states until no open state can improve the goal; false when out of time/budget.
  bool improve_path(double eps, std::uint32_t iteration, AraStarResult& out) {
    std::vector<SearchGraph::Edge> edges;
    while (!open_.empty() && goal_g() > open_.min_key()) {
      if ((expansions_ & 63u) == 0 && p_.time_limit_s > 0.0 && clock_.elapsed_s() > p_.time_limit_s) {
        out.time_exceeded = true;
        return false;
      }
      if (expansions_ >= p_.max_expansions) return false;
      const std::int32_t s = open_.pop();
      rec_[s].closed_in = iteration;
      ++expansions_;
      if (graph_.is_goal(s)) {
        if (rec_[s].g < goal_g()) goal_ = s;
        continue;
      }
      edges.clear();
      graph_.successors(s, edges);
      for (const auto& e : edges) relax(s, e, eps, iteration);
    }
    return true;
  }

  void relax(std::int32_t s, const SearchGraph::Edge& e, double eps, std::uint32_t iteration) {
    touch(e.to);
    Record& r = rec_[e.to];
    const double g = rec_[s].g + e.cost;
    if (g >= r.g || !std::isfinite(r.h)) return;
    r.g = g;
    r.parent = s;
    r.action = static_cast<std::int16_t>(e.action);
    if (graph_.is_goal(e.to) && g < goal_g()) goal_ = e.to;
    if (r.closed_in == iteration) {
      r.incons = true;
      incons_.push_back(e.to);
    } else {
      open_.push_or_update(e.to, key(e.to, eps));
    }
  }

  void reopen(double eps) {
    std::vector<std::int32_t> states = open_.drain();
    for (auto s : incons_)
      if (rec_[s].incons) states.push_back(s);
    incons_.clear();
    for (auto s : states) {
      rec_[s].incons = false;
      open_.push_or_update(s, key(s, eps));
    }
  }

  void publish(double eps, AraStarResult& out) {
    out.found = true;
    out.cost = rec_[goal_].g;
    out.final_epsilon = eps;
    out.states.clear();
    out.actions.clear();
    for (std::int32_t s = goal_; s >= 0; s = rec_[s].parent) {
      out.states.push_back(s);
      if (rec_[s].parent >= 0) out.actions.push_back(rec_[s].action);
    }
    std::reverse(out.states.begin(), out.states.end());
    std::reverse(out.actions.begin(), out.actions.end());
    out.iterations.push_back({eps, out.cost, clock_.elapsed_s(), expansions_});
  }

  SearchGraph& graph_;
  const AraStarParams& p_;
  std::vector<Record> rec_;
  OpenList open_;
  std::vector<std::int32_t> incons_;
  std::int32_t goal_ = -1;
  std::size_t expansions_ = 0;
  SearchClock clock_;
};

}  // namespace

AraStarResult ara_star(SearchGraph& graph, const AraStarParams& params) {
  params.validate();
  Search search(graph, params);
  return search.run();
}

}  // namespace bipednav::planning::footstep
