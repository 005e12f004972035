#include "bipednav/navigation/bt_navigation_leaves.hpp"

namespace bipednav::navigation {
namespace {

std::vector<BtLeafSpec> make_specs() {
  using P = bt::PortSpec;
  const auto C = bt::NodeKind::Condition;
  const auto A = bt::NodeKind::Action;
  const P goal = P::input("goal", bt::BtType::Pose2, "{goal}");
  const P error_code = P::output("error_code", bt::BtType::Int);
  return {
      {"SensorsAlive", C, {}, "every LiDAR and depth camera delivered a frame within its timeout"},
      {"IsLocalizationHealthy", C, {}, "the localization reports good health"},
      {"IsStartValid",
       C,
       {error_code},
       "the robot's centre is on the global map and not in a lethal cell; else error_code = INVALID_START (52) / "
       "BLOCKED_START (54)"},
      {"IsGoalValid",
       C,
       {goal, error_code},
       "the goal is on the map and not in collision; else error_code = BLOCKED_GOAL (55) / OUT_OF_MAP (63)"},
      {"GoalReached", C, {goal}, "the robot is within the goal checker's xy and yaw tolerance of goal and stopped"},
      {"IsPathValid",
       C,
       {P::input("path", bt::BtType::Path, "{path}")},
       "path is non-empty and no lethal cell lies on its next path_check_distance_m"},
      {"CanRotateInPlace", C, {}, "the robot profile allows turning on the spot"},
      {"PlanningRecoveryAllowed",
       C,
       {},
       "admits one more planning recovery while the goal's planning_recoveries_allowed last (each success counts)"},
      {"ComputePathToPose",
       A,
       {goal, P::output("path", bt::BtType::Path), error_code},
       "get_path: plan from the robot to goal; SUCCESS writes path, FAILURE writes the MBF code (50-65)"},
      {"FollowPath",
       A,
       {P::input("path", bt::BtType::Path, "{path}"), error_code},
       "exe_path: follow path, re-reading it every tick (replans); SUCCESS at the goal, FAILURE with the MBF code "
       "(100-118); halted = stop"},
      {"ClearCostmaps", A, {}, "recovery: clear the obstacle layers"},
      {"BackUp",
       A,
       {P::input("distance_m", bt::BtType::Double, "0.3"), P::input("speed_mps", bt::BtType::Double, "0.1")},
       "recovery: drive backwards distance_m at speed_mps"},
      {"RotateInPlace", A, {P::input("angle_rad", bt::BtType::Double, "1.5708")}, "recovery: turn by angle_rad"},
      {"Wait",
       A,
       {P::input("duration_s", bt::BtType::Double, "2.0")},
       "recovery: stand still for duration_s of sim time"},
      {"RelaxConstraints",
       A,
       {},
       "recovery: relax the planner's constraints (e.g. smaller inflation) for the next plans"},
      {"Stop", A, {}, "send a zero velocity command"},
  };
}

}  // namespace

std::vector<BtLeafSpec> navigation_leaf_specs() { return make_specs(); }

bt::Ports bt_leaf_ports(const std::string& id) {
  for (const auto& s : navigation_leaf_specs())
    if (s.id == id) return s.ports;
  throw Error("bt_leaf_ports: '" + id + "' is not a leaf of the default navigation tree");
}

std::vector<std::string> unbound_navigation_leaves(const bt::Factory& factory) {
  std::vector<std::string> out;
  for (const auto& s : navigation_leaf_specs())
    if (!factory.has(s.id)) out.push_back(s.id);
  return out;
}

}  // namespace bipednav::navigation
