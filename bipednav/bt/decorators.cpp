#include "bipednav/bt/decorators.hpp"

#include <cmath>

namespace bipednav::bt {

Status Inverter::tick(double now_s) {
  const Status s = child(0).execute_tick(now_s);
  if (s == Status::RUNNING) return s;
  halt_child(0);
  return s == Status::SUCCESS ? Status::FAILURE : Status::SUCCESS;
}

Status ForceStatus::tick(double now_s) {
  const Status s = child(0).execute_tick(now_s);
  if (s == Status::RUNNING) return s;
  halt_child(0);
  return forced_;
}

Status KeepRunningUntilFailure::tick(double now_s) {
  const Status s = child(0).execute_tick(now_s);
  if (s == Status::RUNNING) return s;
  halt_child(0);
  return s == Status::SUCCESS ? Status::RUNNING : Status::FAILURE;
}

RetryUntilSuccessful::RetryUntilSuccessful(NodeConfig config) : DecoratorNode(std::move(config)) {
  attempts_max_ = bt_int_param(this->config(), "num_attempts");
  if (attempts_max_ == 0 || attempts_max_ < -1) bt_param_error(this->config(), "num_attempts must be >= 1 or -1");
}

Status RetryUntilSuccessful::tick(double now_s) {
  while (attempts_max_ == -1 || attempts_ < attempts_max_) {
    const Status s = child(0).execute_tick(now_s);
    if (s == Status::RUNNING) return s;
    halt_child(0);
    if (s == Status::SUCCESS) {
      attempts_ = 0;
      return s;
    }
    ++attempts_;
  }
  attempts_ = 0;
  return Status::FAILURE;
}

void RetryUntilSuccessful::halt() {
  attempts_ = 0;
  halt_children();
}

RateController::RateController(NodeConfig config)
    : DecoratorNode(std::move(config)),
      gate_(std::get<double>(bt_literal_param(this->config(), "hz", BtType::Double))) {
  const double hz = std::get<double>(bt_literal_param(this->config(), "hz", BtType::Double));
  if (!(hz > 0.0)) bt_param_error(this->config(), "hz must be > 0");
}

Status RateController::tick(double now_s) {
  if (child(0).status() != Status::RUNNING && !gate_.ready(now_s)) return last_child_result_;
  const Status s = child(0).execute_tick(now_s);
  if (s == Status::RUNNING) return s;
  last_child_result_ = s;
  halt_child(0);
  return s;
}

void RateController::halt() {
  // The child was interrupted: tick it again as soon as the node is active again.
  gate_.reset();
  last_child_result_ = Status::SUCCESS;
  halt_children();
}

Delay::Delay(NodeConfig config) : DecoratorNode(std::move(config)), timer_(this->config(), "delay_msec") {}

Status Delay::tick(double now_s) {
  if (!timer_.elapsed(now_s)) return Status::RUNNING;
  const Status s = child(0).execute_tick(now_s);
  if (s == Status::RUNNING) return s;
  timer_.restart();
  halt_child(0);
  return s;
}

void Delay::halt() {
  timer_.restart();
  halt_children();
}

}  // namespace bipednav::bt
