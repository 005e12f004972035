#include "bipednav/bt/factory.hpp"

#include "bipednav/bt/controls.hpp"
#include "bipednav/bt/decorators.hpp"
#include "bipednav/bt/leaves.hpp"

namespace bipednav::bt {
namespace {

template <class NodeT>
Builder make() {
  return [](const NodeConfig& c) { return std::make_unique<NodeT>(c); };
}

NodeType control(Builder b, Ports ports = {}, int min_children = 1, int max_children = -1) {
  return {NodeKind::Control, std::move(b), std::move(ports), min_children, max_children, true};
}

NodeType decorator(Builder b, Ports ports = {}) {
  return {NodeKind::Decorator, std::move(b), std::move(ports), 1, 1, true};
}

NodeType leaf(NodeKind kind, Builder b, Ports ports = {}) { return {kind, std::move(b), std::move(ports), 0, 0, true}; }

Builder force(Status s) {
  return [s](const NodeConfig& c) { return std::make_unique<ForceStatus>(c, s); };
}

Builder sequential(Status stop_on, bool reactive) {
  return [stop_on, reactive](const NodeConfig& c) { return std::make_unique<SequentialNode>(c, stop_on, reactive); };
}

Builder constant(Status s) {
  return [s](const NodeConfig& c) { return std::make_unique<ConstantLeaf>(c, s); };
}

}  // namespace

Factory::Factory() {
  using P = PortSpec;
  add("Sequence", control(sequential(Status::FAILURE, false)));
  add("Fallback", control(sequential(Status::SUCCESS, false)));
  add("ReactiveSequence", control(sequential(Status::FAILURE, true)));
  add("ReactiveFallback", control(sequential(Status::SUCCESS, true)));
  add("Parallel", control(make<Parallel>(),
                          {P::input("success_count", BtType::Int, "-1"), P::input("failure_count", BtType::Int, "1")}));
  add("RecoveryNode", control(make<RecoveryNode>(), {P::input("number_of_retries", BtType::Int, "1")}, 2, 2));
  add("RoundRobin", control(make<RoundRobin>()));
  add("Inverter", decorator(make<Inverter>()));
  add("ForceSuccess", decorator(force(Status::SUCCESS)));
  add("ForceFailure", decorator(force(Status::FAILURE)));
  add("KeepRunningUntilFailure", decorator(make<KeepRunningUntilFailure>()));
  add("RetryUntilSuccessful", decorator(make<RetryUntilSuccessful>(), {P::input("num_attempts", BtType::Int)}));
  add("RateController", decorator(make<RateController>(), {P::input("hz", BtType::Double, "10")}));
  add("Delay", decorator(make<Delay>(), {P::input("delay_msec", BtType::Int)}));
  add("AlwaysSuccess", leaf(NodeKind::Action, constant(Status::SUCCESS)));
  add("AlwaysFailure", leaf(NodeKind::Action, constant(Status::FAILURE)));
  add("Sleep", leaf(NodeKind::Action, make<Sleep>(), {P::input("msec", BtType::Int)}));
  add("SetBlackboard", leaf(NodeKind::Action, make<SetBlackboard>(),
                            {P::input("value", BtType::Any), P::input("output_key", BtType::String)}));
  add("GoalUpdated",
      leaf(NodeKind::Condition, make<GoalUpdated>(),
           {P::input("goal", BtType::Pose2, "{goal}"), P::input("active_goal", BtType::Pose2, "{active_goal}")}));
}

void Factory::add(const std::string& id, NodeType type) {
  if (id.empty() || id == "SubTree") throw Error("BtFactory: invalid node type ID '" + id + "'");
  if (types_.count(id) != 0) throw Error("BtFactory: node type '" + id + "' is already registered");
  if (!type.build) throw Error("BtFactory: node type '" + id + "' has no builder");
  for (const auto& p : type.ports)
    if (p.name.empty() || p.name == "name" || p.name == "ID" || p.name.front() == '_')
      throw Error("BtFactory: node type '" + id + "' declares the reserved port name '" + p.name + "'");
  types_.emplace(id, std::move(type));
}

void Factory::register_action(const std::string& id, Builder build, Ports ports) {
  add(id, {NodeKind::Action, std::move(build), std::move(ports), 0, 0, false});
}

void Factory::register_condition(const std::string& id, Builder build, Ports ports) {
  add(id, {NodeKind::Condition, std::move(build), std::move(ports), 0, 0, false});
}

void Factory::register_simple_condition(const std::string& id, LambdaCondition::Fn fn, Ports ports) {
  if (!fn) throw Error("BtFactory: condition '" + id + "' has no function");
  register_condition(
      id, [fn](const NodeConfig& c) { return std::make_unique<LambdaCondition>(c, fn); }, std::move(ports));
}

void Factory::register_simple_action(const std::string& id, LambdaAction::StepFn step, LambdaAction::HaltFn halted,
                                     Ports ports) {
  if (!step) throw Error("BtFactory: action '" + id + "' has no step function");
  register_action(
      id, [step, halted](const NodeConfig& c) { return std::make_unique<LambdaAction>(c, step, halted); },
      std::move(ports));
}

const NodeType* Factory::find(const std::string& id) const {
  const auto it = types_.find(id);
  return it == types_.end() ? nullptr : &it->second;
}

std::vector<std::string> Factory::ids() const {
  std::vector<std::string> out;
  for (const auto& [id, t] : types_) out.push_back(id);
  return out;
}

}  // namespace bipednav::bt
