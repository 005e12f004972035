#pragma once

#include <ctime>

namespace bipednav {

// CPU time of the whole process (every thread) in milliseconds, for per-stage accounting on a
// shared machine where wall time says little. Never used for control decisions.
inline double process_cpu_ms() {
  timespec ts{};
  if (clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) != 0) return 0.0;
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

// CPU time of the calling thread in milliseconds: unlike wall time it leaves out preemption on a busy
// machine (benchmarks of single-threaded code). Never used for control decisions.
inline double thread_cpu_ms() {
  timespec ts{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return 0.0;
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

// Adds the process CPU time between construction and destruction to `total_ms`.
class CpuScope {
 public:
  explicit CpuScope(double& total_ms) : total_ms_(total_ms), start_ms_(process_cpu_ms()) {}
  ~CpuScope() { total_ms_ += process_cpu_ms() - start_ms_; }
  CpuScope(const CpuScope&) = delete;
  CpuScope& operator=(const CpuScope&) = delete;

 private:
  double& total_ms_;
  double start_ms_;
};

}  // namespace bipednav
