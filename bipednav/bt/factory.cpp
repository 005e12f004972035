#include "bipednav/bt/factory.hpp"

#include "bipednav/bt/controls.hpp"
#include "bipednav/bt/decorators.hpp"
#include "bipednav/bt/leaves.hpp"

namespace bipednav::bt {
namespace {

template <class Node>
BtBuilder make() {
  return [](const BtNodeConfig& c) { return std::make_unique<Node>(c); };
}

BtNodeType control(BtBuilder b, BtPorts ports = {}, int min_children = 1, int max_children = -1) {
  return {BtNodeKind::Control, std::move(b), std::move(ports), min_children, max_children, true};
}

BtNodeType decorator(BtBuilder b, BtPorts ports = {}) {
  return {BtNodeKind::Decorator, std::move(b), std::move(ports), 1, 1, true};
}

BtNodeType leaf(BtNodeKind kind, BtBuilder b, BtPorts ports = {}) {
  return {kind, std::move(b), std::move(ports), 0, 0, true};
}

BtBuilder force(BtStatus s) {
  return [s](const BtNodeConfig& c) { return std::make_unique<BtForceStatus>(c, s); };
}

BtBuilder sequential(BtStatus stop_on, bool reactive) {
  return
      [stop_on, reactive](const BtNodeConfig& c) { return std::make_unique<BtSequentialNode>(c, stop_on, reactive); };
}

BtBuilder constant(BtStatus s) {
  return [s](const BtNodeConfig& c) { return std::make_unique<BtConstantLeaf>(c, s); };
}

}  // namespace

BtFactory::BtFactory() {
  using P = BtPortSpec;
  add("Sequence", control(sequential(BtStatus::FAILURE, false)));
  add("Fallback", control(sequential(BtStatus::SUCCESS, false)));
  add("ReactiveSequence", control(sequential(BtStatus::FAILURE, true)));
  add("ReactiveFallback", control(sequential(BtStatus::SUCCESS, true)));
  add("Parallel", control(make<BtParallel>(),
                          {P::input("success_count", BtType::Int, "-1"), P::input("failure_count", BtType::Int, "1")}));
  add("RecoveryNode", control(make<BtRecoveryNode>(), {P::input("number_of_retries", BtType::Int, "1")}, 2, 2));
  add("RoundRobin", control(make<BtRoundRobin>()));
  add("Inverter", decorator(make<BtInverter>()));
  add("ForceSuccess", decorator(force(BtStatus::SUCCESS)));
  add("ForceFailure", decorator(force(BtStatus::FAILURE)));
  add("KeepRunningUntilFailure", decorator(make<BtKeepRunningUntilFailure>()));
  add("RetryUntilSuccessful", decorator(make<BtRetryUntilSuccessful>(), {P::input("num_attempts", BtType::Int)}));
  add("RateController", decorator(make<BtRateController>(), {P::input("hz", BtType::Double, "10")}));
  add("Delay", decorator(make<BtDelay>(), {P::input("delay_msec", BtType::Int)}));
  add("AlwaysSuccess", leaf(BtNodeKind::Action, constant(BtStatus::SUCCESS)));
  add("AlwaysFailure", leaf(BtNodeKind::Action, constant(BtStatus::FAILURE)));
  add("Sleep", leaf(BtNodeKind::Action, make<BtSleep>(), {P::input("msec", BtType::Int)}));
  add("SetBlackboard", leaf(BtNodeKind::Action, make<BtSetBlackboard>(),
                            {P::input("value", BtType::Any), P::input("output_key", BtType::String)}));
  add("GoalUpdated",
      leaf(BtNodeKind::Condition, make<BtGoalUpdated>(),
           {P::input("goal", BtType::Pose2, "{goal}"), P::input("active_goal", BtType::Pose2, "{active_goal}")}));
}

void BtFactory::add(const std::string& id, BtNodeType type) {
  if (id.empty() || id == "SubTree") throw Error("BtFactory: invalid node type ID '" + id + "'");
  if (types_.count(id) != 0) throw Error("BtFactory: node type '" + id + "' is already registered");
  if (!type.build) throw Error("BtFactory: node type '" + id + "' has no builder");
  for (const auto& p : type.ports)
    if (p.name.empty() || p.name == "name" || p.name == "ID" || p.name.front() == '_')
      throw Error("BtFactory: node type '" + id + "' declares the reserved port name '" + p.name + "'");
  types_.emplace(id, std::move(type));
}

void BtFactory::register_action(const std::string& id, BtBuilder build, BtPorts ports) {
  add(id, {BtNodeKind::Action, std::move(build), std::move(ports), 0, 0, false});
}

void BtFactory::register_condition(const std::string& id, BtBuilder build, BtPorts ports) {
  add(id, {BtNodeKind::Condition, std::move(build), std::move(ports), 0, 0, false});
}

void BtFactory::register_simple_condition(const std::string& id, BtLambdaCondition::Fn fn, BtPorts ports) {
  if (!fn) throw Error("BtFactory: condition '" + id + "' has no function");
  register_condition(
      id, [fn](const BtNodeConfig& c) { return std::make_unique<BtLambdaCondition>(c, fn); }, std::move(ports));
}

void BtFactory::register_simple_action(const std::string& id, BtLambdaAction::StepFn step,
                                       BtLambdaAction::HaltFn halted, BtPorts ports) {
  if (!step) throw Error("BtFactory: action '" + id + "' has no step function");
  register_action(
      id, [step, halted](const BtNodeConfig& c) { return std::make_unique<BtLambdaAction>(c, step, halted); },
      std::move(ports));
}

const BtNodeType* BtFactory::find(const std::string& id) const {
  const auto it = types_.find(id);
  return it == types_.end() ? nullptr : &it->second;
}

std::vector<std::string> BtFactory::ids() const {
  std::vector<std::string> out;
  for (const auto& [id, t] : types_) out.push_back(id);
  return out;
}

}  // namespace bipednav::bt
