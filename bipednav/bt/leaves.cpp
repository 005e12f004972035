#include "bipednav/bt/leaves.hpp"

namespace bipednav::bt {

Sleep::Sleep(NodeConfig config) : Node(std::move(config)), timer_(this->config(), "msec") {}

Status Sleep::tick(double now_s) {
  if (!timer_.elapsed(now_s)) return Status::RUNNING;
  timer_.restart();
  return Status::SUCCESS;
}

void Sleep::halt() { timer_.restart(); }

Status SetBlackboard::tick(double) {
  const auto& ports = config().ports;
  std::string out_key = ports.at("output_key");
  bt_is_reference(out_key, &out_key);
  const std::string& value = ports.at("value");
  std::string src_key;
  if (!bt_is_reference(value, &src_key)) {
    config().blackboard->set_value(out_key, Value(value));
    return Status::SUCCESS;
  }
  const Value* v = config().blackboard->find(src_key);
  if (v == nullptr || std::holds_alternative<std::monostate>(*v)) return Status::FAILURE;
  config().blackboard->set_value(out_key, Value(*v));
  return Status::SUCCESS;
}

bool GoalUpdated::check(double) {
  const auto goal = get_input<Pose2>("goal");
  const auto active = get_input<Pose2>("active_goal");
  if (!goal || !active) return false;
  return goal->x != active->x || goal->y != active->y || goal->theta != active->theta;
}

}  // namespace bipednav::bt
