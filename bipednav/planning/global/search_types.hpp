#pragma once

#include <cstddef>
#include <vector>

#include "bipednav/common/clock.hpp"

namespace bipednav::planning::global {

enum class SearchStatus { kFound, kNoPath, kTimeout };

// What a grid search returns: the cell path (start first) and its cost when found.
struct SearchOutcome {
  SearchStatus status = SearchStatus::kNoPath;
  std::vector<std::size_t> cells;
  double cost = 0.0;
  std::size_t expansions = 0;
};

// A wall-clock budget checked every few hundred expansions (0 = unlimited).
class Deadline {
 public:
  explicit Deadline(double max_ms = 0.0) : max_ms_(max_ms) {}
  bool expired() const { return max_ms_ > 0.0 && watch_.elapsed_ms() > max_ms_; }
  double max_ms() const { return max_ms_; }

 private:
  double max_ms_;
  Stopwatch watch_;
};

inline constexpr std::size_t kDeadlineCheckEvery = 256;

}  // namespace bipednav::planning::global
