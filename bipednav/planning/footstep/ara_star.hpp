#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace bipednav::planning::footstep {

// The implicit graph ARA* searches. States are dense ids handed out by the graph.
class SearchGraph {
 public:
  struct Edge {
    std::int32_t to;
    std::int32_t action;
    double cost;
  };
  virtual ~SearchGraph() = default;
  virtual std::int32_t start_state() = 0;
  virtual void successors(std::int32_t state, std::vector<Edge>& out) = 0;
  virtual double heuristic(std::int32_t state) = 0;
  virtual bool is_goal(std::int32_t state) = 0;
};

// The clock of a search's time limit and reported times: wall time (the default, what a robot
// waits for) or the calling thread's CPU time (benchmarks on a shared machine: the same limit
// buys the same search whatever the load).
enum class SearchClockKind { kWall, kThreadCpu };
const char* search_clock_name(SearchClockKind k);

class SearchClock {
 public:
  explicit SearchClock(SearchClockKind kind = SearchClockKind::kWall);
  double elapsed_s() const { return now_s() - start_s_; }
  SearchClockKind kind() const { return kind_; }

 private:
  double now_s() const;
  SearchClockKind kind_;
  double start_s_;
};

struct AraStarParams {
  double initial_epsilon = 8.0;
  double epsilon_decrease = 0.5;  // eps <- 1 + (eps - 1) * factor after each improved solution
  double time_limit_s = 5.0;      // 0: no limit (search down to target_epsilon)
  double target_epsilon = 1.0;    // stop once a solution with this bound is proven
  std::size_t max_expansions = 20'000'000;
  SearchClockKind clock = SearchClockKind::kWall;  // of time_limit_s and the reported times

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp). clock is left out: it only
  // measures time_limit_s and the reported times, and the closed loop plans without a time limit.
  template <class V>
  void visit_fields(V& v) {
    v("initial_epsilon", initial_epsilon);
    v("epsilon_decrease", epsilon_decrease);
    v("time_limit_s", time_limit_s);
    v("target_epsilon", target_epsilon);
    v("max_expansions", max_expansions);
  }
};

struct AnytimeIteration {
  double epsilon = 0.0;
  double cost = 0.0;
  double time_s = 0.0;
  std::size_t expansions = 0;
};

struct AraStarResult {
  bool found = false;
  bool time_exceeded = false;
  std::vector<std::int32_t> states;   // start .. goal
  std::vector<std::int32_t> actions;  // actions[i] leads from states[i] to states[i + 1]
  double cost = 0.0;
  double final_epsilon = 0.0;
  std::size_t expansions = 0;
  double time_s = 0.0;
  std::vector<AnytimeIteration> iterations;  // one per published solution
};

// Anytime Repairing A* (Likhachev et al.): a weighted A* with inflation epsilon that reuses
// its search effort (INCONS list) while epsilon decreases to 1 within the time limit.
AraStarResult ara_star(SearchGraph& graph, const AraStarParams& params);

}  // namespace bipednav::planning::footstep
