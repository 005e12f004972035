#include "bipednav/bt/decorators.hpp"

#include <cmath>

namespace bipednav::bt {

BtStatus BtInverter::tick(double now_s) {
  const BtStatus s = child(0).execute_tick(now_s);
  if (s == BtStatus::RUNNING) return s;
  halt_child(0);
  return s == BtStatus::SUCCESS ? BtStatus::FAILURE : BtStatus::SUCCESS;
}

BtStatus BtForceStatus::tick(double now_s) {
  const BtStatus s = child(0).execute_tick(now_s);
  if (s == BtStatus::RUNNING) return s;
  halt_child(0);
  return forced_;
}

BtStatus BtKeepRunningUntilFailure::tick(double now_s) {
  const BtStatus s = child(0).execute_tick(now_s);
  if (s == BtStatus::RUNNING) return s;
  halt_child(0);
  return s == BtStatus::SUCCESS ? BtStatus::RUNNING : BtStatus::FAILURE;
}

BtRetryUntilSuccessful::BtRetryUntilSuccessful(BtNodeConfig config) : BtDecoratorNode(std::move(config)) {
  attempts_max_ = bt_int_param(this->config(), "num_attempts");
  if (attempts_max_ == 0 || attempts_max_ < -1) bt_param_error(this->config(), "num_attempts must be >= 1 or -1");
}

BtStatus BtRetryUntilSuccessful::tick(double now_s) {
  while (attempts_max_ == -1 || attempts_ < attempts_max_) {
    const BtStatus s = child(0).execute_tick(now_s);
    if (s == BtStatus::RUNNING) return s;
    halt_child(0);
    if (s == BtStatus::SUCCESS) {
      attempts_ = 0;
      return s;
    }
    ++attempts_;
  }
  attempts_ = 0;
  return BtStatus::FAILURE;
}

void BtRetryUntilSuccessful::halt() {
  attempts_ = 0;
  halt_children();
}

BtRateController::BtRateController(BtNodeConfig config)
    : BtDecoratorNode(std::move(config)),
      gate_(std::get<double>(bt_literal_param(this->config(), "hz", BtType::Double))) {
  const double hz = std::get<double>(bt_literal_param(this->config(), "hz", BtType::Double));
  if (!(hz > 0.0)) bt_param_error(this->config(), "hz must be > 0");
}

BtStatus BtRateController::tick(double now_s) {
  if (child(0).status() != BtStatus::RUNNING && !gate_.ready(now_s)) return last_child_result_;
  const BtStatus s = child(0).execute_tick(now_s);
  if (s == BtStatus::RUNNING) return s;
  last_child_result_ = s;
  halt_child(0);
  return s;
}

void BtRateController::halt() {
  // The child was interrupted: tick it again as soon as the node is active again.
  gate_.reset();
  last_child_result_ = BtStatus::SUCCESS;
  halt_children();
}

BtDelay::BtDelay(BtNodeConfig config) : BtDecoratorNode(std::move(config)), timer_(this->config(), "delay_msec") {}

BtStatus BtDelay::tick(double now_s) {
  if (!timer_.elapsed(now_s)) return BtStatus::RUNNING;
  const BtStatus s = child(0).execute_tick(now_s);
  if (s == BtStatus::RUNNING) return s;
  timer_.restart();
  halt_child(0);
  return s;
}

void BtDelay::halt() {
  timer_.restart();
  halt_children();
}

}  // namespace bipednav::bt
