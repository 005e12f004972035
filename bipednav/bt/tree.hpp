#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bipednav/bt/blackboard.hpp"
#include "bipednav/bt/node.hpp"

namespace bipednav::bt {

// The state of one node, for introspection (HTML replay, run figure, logs).
struct NodeState {
  std::string path;
  std::string id;
  std::string name;
  NodeKind kind = NodeKind::Action;
  Status status = Status::IDLE;
  Status last_result = Status::IDLE;
  double last_tick_s = 0.0;
  int depth = 0;
};

// An instantiated tree: the root node, the root blackboard and the introspection hooks.
// Ticked on the caller's (simulated) clock; never reads the wall clock.
class BehaviorTree {
 public:
  BehaviorTree(std::unique_ptr<Node> root, std::shared_ptr<Blackboard> blackboard, std::unique_ptr<TreeContext> context,
               std::string main_tree_id);
  BehaviorTree(BehaviorTree&&) noexcept = default;
  BehaviorTree& operator=(BehaviorTree&&) noexcept = default;

  // One tick of the whole tree at time now_s (non-decreasing). After the root completed,
  // the next tick starts it afresh.
  Status tick(double now_s);
  // Halts every RUNNING node (actions get on_halted()) and resets the tree to IDLE.
  void halt();
  Status status() const { return root_->status(); }

  const std::shared_ptr<Blackboard>& blackboard() const { return blackboard_; }
  Node& root() { return *root_; }
  const Node& root() const { return *root_; }
  const std::string& main_tree_id() const { return main_tree_id_; }

  // Called on every node status change, with the tick's time.
  void set_observer(Observer observer) { context_->observer = std::move(observer); }

  // The RUNNING leaves (several under a Parallel), in depth-first order.
  std::vector<const Node*> running_leaves() const;
  // Path of the first RUNNING leaf, or of the last leaf ticked when none is running.
  std::string active_leaf() const;
  // Every node in depth-first order.
  std::vector<NodeState> snapshot() const;
  // The node with this path, or nullptr.
  const Node* find(const std::string& path) const;
  // An indented text dump of the snapshot ("Sequence [RUNNING]").
  std::string to_string() const;

 private:
  std::unique_ptr<TreeContext> context_;
  std::unique_ptr<Node> root_;
  std::shared_ptr<Blackboard> blackboard_;
  std::string main_tree_id_;
  double last_now_s_ = -1e300;
};

}  // namespace bipednav::bt
