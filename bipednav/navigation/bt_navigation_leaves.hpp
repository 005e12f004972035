#pragma once

#include <string>
#include <vector>

#include "bipednav/bt/factory.hpp"

// The application leaves config/behavior_trees/navigate.xml uses, with their ports, so the
// navigation server's bindings and the tree cannot drift apart:
//   f.register_action("FollowPath", builder, bt_leaf_ports("FollowPath"));
namespace bipednav::navigation {

struct BtLeafSpec {
  std::string id;
  bt::NodeKind kind = bt::NodeKind::Action;
  bt::Ports ports;
  std::string meaning;  // what the binding must do
};

// Conditions: SensorsAlive, IsLocalizationHealthy, IsStartValid, IsGoalValid, GoalReached,
// IsPathValid, CanRotateInPlace, PlanningRecoveryAllowed. Actions: ComputePathToPose, FollowPath, ClearCostmaps,
// BackUp, RotateInPlace, Wait, RelaxConstraints, Stop. (GoalUpdated is built in.)
std::vector<BtLeafSpec> navigation_leaf_specs();

// The ports of one of these leaves; throws Error for an unknown ID.
bt::Ports bt_leaf_ports(const std::string& id);

// IDs of navigation_leaf_specs() that `factory` does not know yet (empty when all bound).
std::vector<std::string> unbound_navigation_leaves(const bt::Factory& factory);

}  // namespace bipednav::navigation
