#pragma once

#include <chrono>
#include <cstdint>

namespace bipednav {

// Simulated time advanced in fixed steps. Counting steps (not summing floats) keeps times exact.
class SimClock {
 public:
  explicit SimClock(double step_s = 0.01) : step_s_(step_s) {}
  double now_s() const { return static_cast<double>(ticks_) * step_s_; }
  double step_s() const { return step_s_; }
  std::uint64_t ticks() const { return ticks_; }
  void advance() { ++ticks_; }

 private:
  double step_s_;
  std::uint64_t ticks_ = 0;
};

// True every time `now_s` has passed the next multiple of 1/rate_hz since the last trigger.
class RateGate {
 public:
  explicit RateGate(double rate_hz) : period_s_(rate_hz > 0.0 ? 1.0 / rate_hz : 0.0) {}
  bool ready(double now_s) {
    if (!due(now_s)) return false;
    next_s_ = (next_s_ < 0.0 ? now_s : next_s_) + period_s_;
    if (next_s_ <= now_s) next_s_ = now_s + period_s_;
    return true;
  }
  void reset() { next_s_ = -1.0; }
  double period_s() const { return period_s_; }
  // Whether ready(now_s) would pass now (without taking the slot), and the time from which it
  // passes next (-1 before the first ready()).
  bool due(double now_s) const { return !(now_s + 1e-9 < next_s_); }
  double next_s() const { return next_s_; }

 private:
  double period_s_;
  double next_s_ = -1.0;
};

// Wall-clock stopwatch for statistics and benchmarks (never used for control decisions).
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double elapsed_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace bipednav
