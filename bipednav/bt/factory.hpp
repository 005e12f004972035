#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bipednav/bt/node.hpp"

namespace bipednav::bt {

using BtBuilder = std::function<std::unique_ptr<BtNode>(const BtNodeConfig&)>;

// One node type the XML may use.
struct BtNodeType {
  BtNodeKind kind = BtNodeKind::Action;
  BtBuilder build;
  BtPorts ports;  // every attribute besides `name` must be one of these
  int min_children = 0;
  int max_children = 0;  // -1: unlimited
  bool builtin = false;
};

// The explicit table of node types (no static registration). A new factory holds the
// built-in control nodes, decorators and leaves (AlwaysSuccess, AlwaysFailure,
// SetBlackboard, GoalUpdated); the application adds its conditions and actions, each
// with the ports it reads and writes.
class BtFactory {
 public:
  BtFactory();

  void register_action(const std::string& id, BtBuilder build, BtPorts ports = {});
  void register_condition(const std::string& id, BtBuilder build, BtPorts ports = {});
  // A condition given as a function of the node (to read its ports) and the tree time.
  void register_simple_condition(const std::string& id, BtLambdaCondition::Fn fn, BtPorts ports = {});

  // A stateful action given as functions (see BtLambdaAction).
  void register_simple_action(const std::string& id, BtLambdaAction::StepFn step, BtLambdaAction::HaltFn halted = {},
                              BtPorts ports = {});

  const BtNodeType* find(const std::string& id) const;
  bool has(const std::string& id) const { return find(id) != nullptr; }
  std::vector<std::string> ids() const;

 private:
  void add(const std::string& id, BtNodeType type);
  std::map<std::string, BtNodeType> types_;
};

}  // namespace bipednav::bt
