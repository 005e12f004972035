#pragma once

#include "bipednav/bt/node.hpp"
#include "bipednav/common/clock.hpp"

// Decorators (BehaviorTree.CPP v4 semantics; RateController as in Nav2, on the tree's
// simulated clock) and the SubTree node; the engine's built-in leaves are in leaves.hpp.
namespace bipednav::bt {

class BtDecoratorNode : public BtNode {
 public:
  using BtNode::BtNode;
  BtNodeKind kind() const override { return BtNodeKind::Decorator; }

 protected:
  void halt() override { halt_children(); }
};

// SUCCESS <-> FAILURE; RUNNING passes.
class BtInverter final : public BtDecoratorNode {
 public:
  using BtDecoratorNode::BtDecoratorNode;

 protected:
  BtStatus tick(double now_s) override;
};

// Any completed child status becomes `forced_` (SUCCESS or FAILURE); RUNNING passes.
class BtForceStatus final : public BtDecoratorNode {
 public:
  BtForceStatus(BtNodeConfig config, BtStatus forced) : BtDecoratorNode(std::move(config)), forced_(forced) {}

 protected:
  BtStatus tick(double now_s) override;

 private:
  BtStatus forced_;
};

// RUNNING while the child succeeds or runs (the child restarts after each SUCCESS); FAILURE
// when it fails.
class BtKeepRunningUntilFailure final : public BtDecoratorNode {
 public:
  using BtDecoratorNode::BtDecoratorNode;

 protected:
  BtStatus tick(double now_s) override;
};

// Restarts a failing child up to num_attempts times in total (-1: without limit).
class BtRetryUntilSuccessful final : public BtDecoratorNode {
 public:
  explicit BtRetryUntilSuccessful(BtNodeConfig config);

 protected:
  BtStatus tick(double now_s) override;
  void halt() override;

 private:
  int attempts_max_ = 1;
  int attempts_ = 0;
};

// Ticks the child at most hz times per second of simulated time; once started the child is
// ticked every tick until it completes. While throttled, returns the child's last result, so
// it can sit in a ReactiveSequence beside a running action without halting it.
class BtRateController final : public BtDecoratorNode {
 public:
  explicit BtRateController(BtNodeConfig config);

 protected:
  BtStatus tick(double now_s) override;
  void halt() override;

 private:
  RateGate gate_;
  BtStatus last_child_result_ = BtStatus::SUCCESS;
};

// RUNNING for delay_msec of simulated time after activation, then behaves like the child.
class BtDelay final : public BtDecoratorNode {
 public:
  explicit BtDelay(BtNodeConfig config);

 protected:
  BtStatus tick(double now_s) override;
  void halt() override;

 private:
  BtSimTimer timer_;
};

// The root of another BehaviorTree, on its own (remapped) blackboard; status passes through.
class BtSubTreeNode final : public BtNode {
 public:
  using BtNode::BtNode;
  BtNodeKind kind() const override { return BtNodeKind::SubTree; }

 protected:
  BtStatus tick(double now_s) override { return child(0).execute_tick(now_s); }
  void halt() override { halt_children(); }
};

}  // namespace bipednav::bt
