#pragma once

#include <set>

#include "bipednav/navigation/bt_node.hpp"

// Composite (control) nodes with BehaviorTree.CPP v4 semantics, plus Nav2's RecoveryNode
// and RoundRobin. Parents reset (halt) their children whenever they complete.
namespace bipednav::navigation {

class BtControlNode : public BtNode {
 public:
  using BtNode::BtNode;
  BtNodeKind kind() const override { return BtNodeKind::Control; }

 protected:
  void halt() override { halt_children(); }
};

// Ticks children in order; remembers the RUNNING child (it resumes there next tick).
class BtSequence final : public BtControlNode {
 public:
  using BtControlNode::BtControlNode;

 protected:
  BtStatus tick(double now_s) override;
  void halt() override;

 private:
  std::size_t current_ = 0;
};

// Ticks children in order until one does not fail; remembers the RUNNING child.
class BtFallback final : public BtControlNode {
 public:
  using BtControlNode::BtControlNode;

 protected:
  BtStatus tick(double now_s) override;
  void halt() override;

 private:
  std::size_t current_ = 0;
};

// Re-evaluates every child from the first on each tick; a RUNNING child halts all others,
// a FAILURE halts the RUNNING one.
class BtReactiveSequence final : public BtControlNode {
 public:
  using BtControlNode::BtControlNode;

 protected:
  BtStatus tick(double now_s) override;
};

// Re-evaluates every child from the first on each tick; a RUNNING child halts all others,
// a SUCCESS halts the RUNNING one.
class BtReactiveFallback final : public BtControlNode {
 public:
  using BtControlNode::BtControlNode;

 protected:
  BtStatus tick(double now_s) override;
};

// Ticks every unfinished child each tick; SUCCESS once success_count children succeeded,
// FAILURE once failure_count failed (or success became impossible). Negative thresholds
// count from the number of children (-1 = all). Completion halts the still-running children.
class BtParallel final : public BtControlNode {
 public:
  explicit BtParallel(BtNodeConfig config);
  // Checks the thresholds against the number of children (called once the children exist).
  void validate_children() const;

 protected:
  BtStatus tick(double now_s) override;
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
class BtRecoveryNode final : public BtControlNode {
 public:
  explicit BtRecoveryNode(BtNodeConfig config);

 protected:
  BtStatus tick(double now_s) override;
  void halt() override;

 private:
  int retries_max_ = 1;
  int retries_ = 0;
  std::size_t current_ = 0;
};

// Nav2's RoundRobin: each activation starts at the child after the one that last succeeded,
// so consecutive recoveries cycle through the children. FAILURE when all children failed.
class BtRoundRobin final : public BtControlNode {
 public:
  using BtControlNode::BtControlNode;

 protected:
  BtStatus tick(double now_s) override;
  void halt() override;

 private:
  std::size_t current_ = 0;
  std::size_t failures_ = 0;
};

}  // namespace bipednav::navigation
