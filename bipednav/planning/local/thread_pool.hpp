#pragma once

#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace bipednav::planning::local {

// A small fixed-size pool running index-parallel loops. Each job writes only to its own slot, so
// results do not depend on scheduling. With one thread the loop runs inline on the caller.
class ThreadPool {
 public:
  explicit ThreadPool(int num_threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return num_threads_; }
  // Calls fn(i) for i in [0, n) and returns when all calls finished. Exceptions are rethrown.
  void parallel_for(std::size_t n, const std::function<void(std::size_t)>& fn);

 private:
  void worker();

  int num_threads_;
  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable cv_work_, cv_done_;
  const std::function<void(std::size_t)>* job_ = nullptr;
  std::size_t job_size_ = 0, next_ = 0, done_ = 0;
  std::size_t generation_ = 0;
  bool stop_ = false;
  std::exception_ptr error_;
};

}  // namespace bipednav::planning::local
