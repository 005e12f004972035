#pragma once

#include "bipednav/bt/node.hpp"
#include "bipednav/common/clock.hpp"

// Decorators (BehaviorTree.CPP v4 semantics; RateController as in Nav2, on the tree's
// simulated clock) and the SubTree node; the engine's built-in leaves are in leaves.hpp.
namespace bipednav::bt {

class DecoratorNode : public Node {
 public:
  using Node::Node;
  NodeKind kind() const override { return NodeKind::Decorator; }

 protected:
  void halt() override { halt_children(); }
};

// SUCCESS <-> FAILURE; RUNNING passes.
class Inverter final : public DecoratorNode {
 public:
  using DecoratorNode::DecoratorNode;

 protected:
  Status tick(double now_s) override;
};

// Any completed child status becomes `forced_` (SUCCESS or FAILURE); RUNNING passes.
class ForceStatus final : public DecoratorNode {
 public:
  ForceStatus(NodeConfig config, Status forced) : DecoratorNode(std::move(config)), forced_(forced) {}

 protected:
  Status tick(double now_s) override;

 private:
  Status forced_;
};

// RUNNING while the child succeeds or runs (the child restarts after each SUCCESS); FAILURE
// when it fails.
class KeepRunningUntilFailure final : public DecoratorNode {
 public:
  using DecoratorNode::DecoratorNode;

 protected:
  Status tick(double now_s) override;
};

// Restarts a failing child up to num_attempts times in total (-1: without limit).
class RetryUntilSuccessful final : public DecoratorNode {
 public:
  explicit RetryUntilSuccessful(NodeConfig config);

 protected:
  Status tick(double now_s) override;
  void halt() override;

 private:
  int attempts_max_ = 1;
  int attempts_ = 0;
};

// Ticks the child at most hz times per second of simulated time; once started the child is
// ticked every tick until it completes. While throttled, returns the child's last result, so
// it can sit in a ReactiveSequence beside a running action without halting it.
class RateController final : public DecoratorNode {
 public:
  explicit RateController(NodeConfig config);

 protected:
  Status tick(double now_s) override;
  void halt() override;

 private:
  RateGate gate_;
  Status last_child_result_ = Status::SUCCESS;
};

// RUNNING for delay_msec of simulated time after activation, then behaves like the child.
class Delay final : public DecoratorNode {
 public:
  explicit Delay(NodeConfig config);

 protected:
  Status tick(double now_s) override;
  void halt() override;

 private:
  SimTimer timer_;
};

// The root of another BehaviorTree, on its own (remapped) blackboard; status passes through.
class SubTreeNode final : public Node {
 public:
  using Node::Node;
  NodeKind kind() const override { return NodeKind::SubTree; }

 protected:
  Status tick(double now_s) override { return child(0).execute_tick(now_s); }
  void halt() override { halt_children(); }
};

}  // namespace bipednav::bt
