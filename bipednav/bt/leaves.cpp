#include "bipednav/bt/leaves.hpp"

namespace bipednav::bt {

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

}  // namespace bipednav::bt
