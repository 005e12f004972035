#pragma once

#include <set>

#include "bipednav/bt/node.hpp"

// Composite (control) nodes with BehaviorTree.CPP v4 semantics, plus Nav2's RecoveryNode
// and RoundRobin. Parents reset (halt) their children whenever they complete.
namespace bipednav::bt {

class ControlNode : public Node {
 public:
  using Node::Node;
  NodeKind kind() const override { return NodeKind::Control; }

 protected:
  void halt() override { halt_children(); }
};

// Sequence (stop_on = FAILURE) and Fallback (stop_on = SUCCESS): ticks the children in order
// until one returns stop_on, which ends the node with that status; when all children return
// the other status the node does too.
//  - memory (Sequence, Fallback): a RUNNING child is resumed on the next tick without
//    re-ticking the children before it.
//  - reactive (ReactiveSequence, ReactiveFallback): every tick starts from the first child;
//    a RUNNING child halts all other children, so an earlier child that changes its result
//    halts the later running one.
class SequentialNode final : public ControlNode {
 public:
  SequentialNode(NodeConfig config, Status stop_on, bool reactive)
      : ControlNode(std::move(config)), stop_on_(stop_on), reactive_(reactive) {}

 protected:
  Status tick(double now_s) override;
  void halt() override;

 private:
  Status finish(Status s);

  Status stop_on_;
  bool reactive_;
  std::size_t current_ = 0;
};

// Ticks every unfinished child each tick; SUCCESS once success_count children succeeded,
// FAILURE once failure_count failed (or success became impossible). Negative thresholds
// count from the number of children (-1 = all). Completion halts the still-running children.
class Parallel final : public ControlNode {
 public:
  explicit Parallel(NodeConfig config);
  // Checks the thresholds against the number of children (called once the children exist).
  void validate_children() const;

 protected:
  Status tick(double now_s) override;
  void halt() override;

 private:
  std::size_t threshold(int t) const;
  void clear();

  int success_threshold_ = -1;
  int failure_threshold_ = 1;
  std::set<std::size_t> completed_;
  std::size_t successes_ = 0;
  std::size_t failures_ = 0;
};

// Nav2's RecoveryNode: child 0 is the main task, child 1 the recovery. When the main task
// fails, the recovery runs; if it succeeds the main task is retried, at most
// number_of_retries times. A failing recovery fails the node.
class RecoveryNode final : public ControlNode {
 public:
  explicit RecoveryNode(NodeConfig config);

 protected:
  Status tick(double now_s) override;
  void halt() override;

 private:
  int retries_max_ = 1;
  int retries_ = 0;
  std::size_t current_ = 0;
};

// Nav2's RoundRobin: each activation starts at the child after the one that last succeeded,
// so consecutive recoveries cycle through the children. FAILURE when all children failed.
class RoundRobin final : public ControlNode {
 public:
  using ControlNode::ControlNode;

 protected:
  Status tick(double now_s) override;
  void halt() override;

 private:
  std::size_t current_ = 0;
  std::size_t failures_ = 0;
};

}  // namespace bipednav::bt
