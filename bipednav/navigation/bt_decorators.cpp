#include "bipednav/navigation/bt_decorators.hpp"

#include <cmath>

namespace bipednav::navigation {
namespace {

int int_param(const BtNodeConfig& c, const std::string& port) {
  return std::get<int>(bt_literal_param(c, port, BtType::Int));
}

[[noreturn]] void bad_param(const BtNodeConfig& c, const std::string& what) {
  throw FileError(c.file, std::to_string(c.line), c.id + ": " + what);
}

}  // namespace

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
  attempts_max_ = int_param(this->config(), "num_attempts");
  if (attempts_max_ == 0 || attempts_max_ < -1) bad_param(this->config(), "num_attempts must be >= 1 or -1");
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
  if (!(hz > 0.0)) bad_param(this->config(), "hz must be > 0");
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

BtSimTimer::BtSimTimer(const BtNodeConfig& config, const std::string& msec_port) {
  const int ms = int_param(config, msec_port);
  if (ms < 0) bad_param(config, msec_port + " must be >= 0");
  duration_s_ = ms * 1e-3;
}

bool BtSimTimer::elapsed(double now_s) {
  if (!started_) {
    started_ = true;
    start_s_ = now_s;
  }
  return !(now_s - start_s_ + 1e-9 < duration_s_);
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

BtSleep::BtSleep(BtNodeConfig config) : BtNode(std::move(config)), timer_(this->config(), "msec") {}

BtStatus BtSleep::tick(double now_s) {
  if (!timer_.elapsed(now_s)) return BtStatus::RUNNING;
  timer_.restart();
  return BtStatus::SUCCESS;
}

void BtSleep::halt() { timer_.restart(); }

BtStatus BtSetBlackboard::tick(double) {
  const auto& ports = config().ports;
  std::string out_key = ports.at("output_key");
  bt_is_reference(out_key, &out_key);
  const std::string& value = ports.at("value");
  std::string src_key;
  if (!bt_is_reference(value, &src_key)) {
    config().blackboard->set_value(out_key, BtValue(value));
    return BtStatus::SUCCESS;
  }
  const BtValue* v = config().blackboard->find(src_key);
  if (v == nullptr || std::holds_alternative<std::monostate>(*v)) return BtStatus::FAILURE;
  config().blackboard->set_value(out_key, BtValue(*v));
  return BtStatus::SUCCESS;
}

bool BtGoalUpdated::check(double) {
  const auto goal = get_input<Pose2>("goal");
  const auto active = get_input<Pose2>("active_goal");
  if (!goal || !active) return false;
  return goal->x != active->x || goal->y != active->y || goal->theta != active->theta;
}

}  // namespace bipednav::navigation
