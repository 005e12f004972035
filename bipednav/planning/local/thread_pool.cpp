#include "bipednav/planning/local/thread_pool.hpp"

#include <exception>

namespace bipednav::planning::local {

ThreadPool::ThreadPool(int num_threads) : num_threads_(num_threads < 1 ? 1 : num_threads) {
  // The caller takes part in every loop, so one thread means no worker at all.
  for (int i = 1; i < num_threads_; ++i) threads_.emplace_back([this] { worker(); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  cv_work_.notify_all();
  for (auto& t : threads_) t.join();
}

void ThreadPool::worker() {
  std::size_t seen = 0;
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    cv_work_.wait(lock, [&] { return stop_ || (generation_ != seen && next_ < job_size_); });
    if (stop_) return;
    while (next_ < job_size_) {
      const std::size_t i = next_++;
      lock.unlock();
      try {
        (*job_)(i);
      } catch (...) {
        std::lock_guard<std::mutex> g(mutex_);
        if (!error_) error_ = std::current_exception();
      }
      lock.lock();
      if (++done_ == job_size_) cv_done_.notify_all();
    }
    seen = generation_;
  }
}

void ThreadPool::parallel_for(std::size_t n, const std::function<void(std::size_t)>& fn) {
  if (n == 0) return;
  if (threads_.empty() || n == 1) {
    for (std::size_t i = 0; i < n; ++i) fn(i);
    return;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  job_ = &fn;
  job_size_ = n;
  next_ = 0;
  done_ = 0;
  error_ = nullptr;
  ++generation_;
  cv_work_.notify_all();
  // The caller works too.
  while (next_ < job_size_) {
    const std::size_t i = next_++;
    lock.unlock();
    try {
      fn(i);
    } catch (...) {
      std::lock_guard<std::mutex> g(mutex_);
      if (!error_) error_ = std::current_exception();
    }
    lock.lock();
    ++done_;
  }
  cv_done_.wait(lock, [&] { return done_ == job_size_; });
  job_ = nullptr;
  job_size_ = 0;
  if (error_) std::rethrow_exception(error_);
}

}  // namespace bipednav::planning::local
