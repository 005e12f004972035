#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bipednav/bt/node.hpp"

namespace bipednav::bt {

using Builder = std::function<std::unique_ptr<Node>(const NodeConfig&)>;

// One node type the XML may use.
struct NodeType {
  NodeKind kind = NodeKind::Action;
  Builder build;
  Ports ports;  // every attribute besides `name` must be one of these
  int min_children = 0;
  int max_children = 0;  // -1: unlimited
  bool builtin = false;
};

// The explicit table of node types (no static registration). A new factory holds the
// built-in control nodes, decorators and leaves (AlwaysSuccess, AlwaysFailure,
// SetBlackboard, GoalUpdated); the application adds its conditions and actions, each
// with the ports it reads and writes.
class Factory {
 public:
  Factory();

  void register_action(const std::string& id, Builder build, Ports ports = {});
  void register_condition(const std::string& id, Builder build, Ports ports = {});
  // A condition given as a function of the node (to read its ports) and the tree time.
  void register_simple_condition(const std::string& id, LambdaCondition::Fn fn, Ports ports = {});

  // A stateful action given as functions (see LambdaAction).
  void register_simple_action(const std::string& id, LambdaAction::StepFn step, LambdaAction::HaltFn halted = {},
                              Ports ports = {});

  const NodeType* find(const std::string& id) const;
  bool has(const std::string& id) const { return find(id) != nullptr; }
  std::vector<std::string> ids() const;

 private:
  void add(const std::string& id, NodeType type);
  std::map<std::string, NodeType> types_;
};

}  // namespace bipednav::bt
