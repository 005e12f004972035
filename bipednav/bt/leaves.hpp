#pragma once

#include "bipednav/bt/node.hpp"

namespace bipednav::bt {

// The engine's built-in leaves (BehaviorTree.CPP v4 names): AlwaysSuccess / AlwaysFailure, Sleep,
// SetBlackboard, and the navigation tree's GoalUpdated condition.

// AlwaysSuccess / AlwaysFailure.
class BtConstantLeaf final : public BtNode {
 public:
  BtConstantLeaf(BtNodeConfig config, BtStatus result) : BtNode(std::move(config)), result_(result) {}
  BtNodeKind kind() const override { return BtNodeKind::Action; }

 protected:
  BtStatus tick(double) override { return result_; }

 private:
  BtStatus result_;
};

// Sleep msec="N" (BehaviorTree.CPP v4's built-in): RUNNING for msec of simulated time after
// activation, then SUCCESS; a halt restarts the count. A timer that is no recovery (the safety
// gate's wait for sensor health; the Wait recovery is an MBF recovery with an outcome code).
class BtSleep final : public BtNode {
 public:
  explicit BtSleep(BtNodeConfig config);
  BtNodeKind kind() const override { return BtNodeKind::Action; }

 protected:
  BtStatus tick(double now_s) override;
  void halt() override;

 private:
  BtSimTimer timer_;
};

// SetBlackboard value="42"|"{other_key}" output_key="key": copies a literal (as a string)
// or another entry (keeping its type) into output_key. Fails when the source is absent.
class BtSetBlackboard final : public BtNode {
 public:
  using BtNode::BtNode;
  BtNodeKind kind() const override { return BtNodeKind::Action; }

 protected:
  BtStatus tick(double now_s) override;
};

// GoalUpdated goal="{goal}" active_goal="{active_goal}": SUCCESS while both are set and
// differ (a new goal arrived since the running navigation copied it to active_goal).
class BtGoalUpdated final : public BtCondition {
 public:
  using BtCondition::BtCondition;

 protected:
  bool check(double now_s) override;
};

}  // namespace bipednav::bt
