#include "bipednav/bt/controls.hpp"

#include <algorithm>

#include "bipednav/common/error.hpp"

namespace bipednav::bt {

Status SequentialNode::finish(Status s) {
  halt_children();
  current_ = 0;
  return s;
}

Status SequentialNode::tick(double now_s) {
  const Status all_done = stop_on_ == Status::FAILURE ? Status::SUCCESS : Status::FAILURE;
  for (std::size_t i = reactive_ ? 0 : current_; i < child_count(); ++i) {
    const Status s = child(i).execute_tick(now_s);
    if (s == stop_on_) return finish(s);
    if (s == Status::RUNNING) {
      if (reactive_)
        for (std::size_t j = 0; j < child_count(); ++j)
          if (j != i) halt_child(j);
      current_ = i;
      return s;
    }
  }
  return finish(all_done);
}

void SequentialNode::halt() { finish(Status::IDLE); }

Parallel::Parallel(NodeConfig config) : ControlNode(std::move(config)) {
  success_threshold_ = std::get<int>(bt_literal_param(this->config(), "success_count", BtType::Int));
  failure_threshold_ = std::get<int>(bt_literal_param(this->config(), "failure_count", BtType::Int));
}

std::size_t Parallel::threshold(int t) const {
  const auto n = static_cast<int>(child_count());
  return static_cast<std::size_t>(t < 0 ? std::max(n + t + 1, 0) : t);
}

void Parallel::validate_children() const {
  const std::size_t n = child_count();
  for (const int t : {success_threshold_, failure_threshold_})
    if (t == 0 || threshold(t) > n || threshold(t) == 0)
      throw FileError(config().file, std::to_string(config().line),
                      "Parallel: success_count/failure_count " + std::to_string(t) + " must be in [1, " +
                          std::to_string(n) + "] or in [-" + std::to_string(n) + ", -1] for " + std::to_string(n) +
                          " children");
}

void Parallel::clear() {
  completed_.clear();
  successes_ = failures_ = 0;
}

Status Parallel::tick(double now_s) {
  const std::size_t n = child_count();
  const std::size_t need_success = threshold(success_threshold_);
  const std::size_t need_failure = threshold(failure_threshold_);
  for (std::size_t i = 0; i < n; ++i) {
    if (completed_.count(i) != 0) continue;
    const Status s = child(i).execute_tick(now_s);
    if (s == Status::SUCCESS) ++successes_;
    if (s == Status::FAILURE) ++failures_;
    if (s != Status::RUNNING) completed_.insert(i);
    if (successes_ >= need_success) {
      clear();
      halt_children();
      return Status::SUCCESS;
    }
    if (failures_ >= need_failure || n - failures_ < need_success) {
      clear();
      halt_children();
      return Status::FAILURE;
    }
  }
  return Status::RUNNING;
}

void Parallel::halt() {
  clear();
  halt_children();
}

RecoveryNode::RecoveryNode(NodeConfig config) : ControlNode(std::move(config)) {
  retries_max_ = std::get<int>(bt_literal_param(this->config(), "number_of_retries", BtType::Int));
  if (retries_max_ < 0)
    throw FileError(this->config().file, std::to_string(this->config().line),
                    "RecoveryNode: number_of_retries must be >= 0, got " + std::to_string(retries_max_));
}

Status RecoveryNode::tick(double now_s) {
  while (true) {
    const Status s = child(current_).execute_tick(now_s);
    if (s == Status::RUNNING) return s;
    if (current_ == 0) {
      if (s == Status::SUCCESS || retries_ >= retries_max_) {
        halt();
        return s;
      }
      halt_child(0);
      current_ = 1;
    } else {
      if (s == Status::FAILURE) {
        halt();
        return s;
      }
      halt_child(1);
      ++retries_;
      current_ = 0;
    }
  }
}

void RecoveryNode::halt() {
  retries_ = 0;
  current_ = 0;
  halt_children();
}

Status RoundRobin::tick(double now_s) {
  const std::size_t n = child_count();
  while (failures_ < n) {
    const Status s = child(current_).execute_tick(now_s);
    if (s == Status::RUNNING) return s;
    current_ = (current_ + 1) % n;
    if (s == Status::SUCCESS) {
      failures_ = 0;
      halt_children();
      return s;
    }
    ++failures_;
  }
  failures_ = 0;
  halt_children();
  return Status::FAILURE;
}

void RoundRobin::halt() {
  failures_ = 0;
  halt_children();
}

}  // namespace bipednav::bt
