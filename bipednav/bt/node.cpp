#include "bipednav/bt/node.hpp"

#include "bipednav/common/error.hpp"

namespace bipednav::bt {

std::string_view bt_status_name(Status s) {
  switch (s) {
    case Status::IDLE:
      return "IDLE";
    case Status::RUNNING:
      return "RUNNING";
    case Status::SUCCESS:
      return "SUCCESS";
    case Status::FAILURE:
      return "FAILURE";
  }
  return "?";
}

std::string_view bt_kind_name(NodeKind k) {
  switch (k) {
    case NodeKind::Action:
      return "Action";
    case NodeKind::Condition:
      return "Condition";
    case NodeKind::Control:
      return "Control";
    case NodeKind::Decorator:
      return "Decorator";
    case NodeKind::SubTree:
      return "SubTree";
  }
  return "?";
}

Status Node::execute_tick(double now_s) {
  last_tick_s_ = now_s;
  const Status s = tick(now_s);
  if (s == Status::IDLE) throw Error(describe() + ": tick() returned IDLE");
  last_result_ = s;
  set_status(s, now_s);
  return s;
}

void Node::halt_node() {
  if (status_ == Status::RUNNING) halt();
  set_status(Status::IDLE, last_tick_s_);
}

void Node::halt_children() {
  for (auto& c : children_) c->halt_node();
}

void Node::set_status(Status s, double now_s) {
  if (s == status_) return;
  const Status previous = status_;
  status_ = s;
  if (config_.context != nullptr && config_.context->observer) config_.context->observer(*this, previous, s, now_s);
}

std::string Node::describe() const {
  std::string d = config_.id;
  if (config_.name != config_.id) d += " '" + config_.name + "'";
  if (!config_.file.empty()) d += " (" + config_.file + ":" + std::to_string(config_.line) + ")";
  return d;
}

std::optional<Value> Node::input_value(const std::string& port, BtType type) const {
  const auto it = config_.ports.find(port);
  if (it == config_.ports.end()) return std::nullopt;
  std::string key;
  if (bt_is_reference(it->second, &key)) {
    if (!config_.blackboard) return std::nullopt;
    const Value* v = config_.blackboard->find(key);
    if (v == nullptr || std::holds_alternative<std::monostate>(*v)) return std::nullopt;
    return bt_convert(*v, type, describe() + ": port '" + port + "' ({" + key + "})");
  }
  return bt_convert(Value(it->second), type, describe() + ": port '" + port + "'");
}

void Node::write_output(const std::string& port, Value value) {
  const auto it = config_.ports.find(port);
  std::string key;
  if (it == config_.ports.end() || !bt_is_reference(it->second, &key))
    throw Error(describe() + ": output port '" + port + "' is not connected to a blackboard key");
  config_.blackboard->set_value(key, std::move(value));
}

Value bt_literal_param(const NodeConfig& config, const std::string& port, BtType type) {
  const auto it = config.ports.find(port);
  const std::string where = std::to_string(config.line);
  if (it == config.ports.end()) throw FileError(config.file, where, config.id + ": missing attribute '" + port + "'");
  auto v = bt_is_reference(it->second) ? std::nullopt : bt_parse_literal(it->second, type);
  if (!v)
    throw FileError(config.file, where,
                    config.id + ": attribute " + port + "=\"" + it->second + "\" is not a literal " +
                        std::string(bt_type_name(type)));
  return *v;
}

Status StatefulAction::tick(double now_s) { return status() == Status::RUNNING ? on_running(now_s) : on_start(now_s); }

int bt_int_param(const NodeConfig& config, const std::string& port) {
  return std::get<int>(bt_literal_param(config, port, BtType::Int));
}

void bt_param_error(const NodeConfig& config, const std::string& what) {
  throw FileError(config.file, std::to_string(config.line), config.id + ": " + what);
}

SimTimer::SimTimer(const NodeConfig& config, const std::string& msec_port) {
  const int ms = bt_int_param(config, msec_port);
  if (ms < 0) bt_param_error(config, msec_port + " must be >= 0");
  duration_s_ = ms * 1e-3;
}

bool SimTimer::elapsed(double now_s) {
  if (!started_) {
    started_ = true;
    start_s_ = now_s;
  }
  return !(now_s - start_s_ + 1e-9 < duration_s_);
}

}  // namespace bipednav::bt
