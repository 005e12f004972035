#pragma once

#include "bipednav/bt/node.hpp"

namespace bipednav::bt {

// The engine's built-in leaves (BehaviorTree.CPP v4 names): AlwaysSuccess / AlwaysFailure, Sleep,
// SetBlackboard, and the navigation tree's GoalUpdated condition.

// AlwaysSuccess / AlwaysFailure.
class ConstantLeaf final : public Node {
 public:
  ConstantLeaf(NodeConfig config, Status result) : Node(std::move(config)), result_(result) {}
  NodeKind kind() const override { return NodeKind::Action; }

 protected:
  Status tick(double) override { return result_; }

 private:
  Status result_;
};

// Sleep msec="N" (BehaviorTree.CPP v4's built-in): RUNNING for msec of simulated time after
// activation, then SUCCESS; a halt restarts the count. A timer that is no recovery (the safety
// gate's wait for sensor health; the Wait recovery is an MBF recovery with an outcome code).
class Sleep final : public Node {
 public:
  explicit Sleep(NodeConfig config);
  NodeKind kind() const override { return NodeKind::Action; }

 protected:
  Status tick(double now_s) override;
  void halt() override;

 private:
  SimTimer timer_;
};

// SetBlackboard value="42"|"{other_key}" output_key="key": copies a literal (as a string)
// or another entry (keeping its type) into output_key. Fails when the source is absent.
class SetBlackboard final : public Node {
 public:
  using Node::Node;
  NodeKind kind() const override { return NodeKind::Action; }

 protected:
  Status tick(double now_s) override;
};

// GoalUpdated goal="{goal}" active_goal="{active_goal}": SUCCESS while both are set and
// differ (a new goal arrived since the running navigation copied it to active_goal).
class GoalUpdated final : public Condition {
 public:
  using Condition::Condition;

 protected:
  bool check(double now_s) override;
};

}  // namespace bipednav::bt
