// The behavior tree's application leaves (bt_navigation_leaves.hpp lists them with their
// ports), bound to the navigation server and the navigator's health checks.
#include "bipednav/navigation/bt_navigation_leaves.hpp"
#include "bipednav/navigation/navigator.hpp"

namespace bipednav::navigation {

namespace {

bt::Status to_status(const ActionStep& step) {
  switch (step.state) {
    case ActionStep::State::RUNNING:
      return bt::Status::RUNNING;
    case ActionStep::State::SUCCEEDED:
      return bt::Status::SUCCESS;
    case ActionStep::State::FAILED:
      return bt::Status::FAILURE;
  }
  return bt::Status::FAILURE;
}

// The conditions on the navigation server's state (a failed start or goal check reports its outcome).
template <class FailWith>
void register_server_conditions(bt::Factory& f, NavigationServer& srv, const FailWith& fail_with) {
  f.register_simple_condition(
      "IsStartValid",
      [&srv, fail_with](bt::Node& self, double) {
        const Result r = srv.start_valid();
        if (!r.ok()) fail_with(self, r);
        return r.ok();
      },
      bt_leaf_ports("IsStartValid"));
  f.register_simple_condition(
      "IsGoalValid",
      [&srv, fail_with](bt::Node& self, double) {
        const Result r = srv.goal_valid(self.input<Pose2>("goal"));
        if (!r.ok()) fail_with(self, r);
        return r.ok();
      },
      bt_leaf_ports("IsGoalValid"));
  f.register_simple_condition(
      "GoalReached", [&srv](bt::Node& self, double) { return srv.goal_reached(self.input<Pose2>("goal")); },
      bt_leaf_ports("GoalReached"));
  f.register_simple_condition(
      "IsPathValid",
      [&srv](bt::Node& self, double) {
        const auto p = self.get_input<Path>("path");
        return p && srv.path_valid(*p);
      },
      bt_leaf_ports("IsPathValid"));
  f.register_simple_condition(
      "CanRotateInPlace", [&srv](bt::Node&, double) { return srv.can_rotate_in_place(); },
      bt_leaf_ports("CanRotateInPlace"));
  f.register_simple_condition(
      "PlanningRecoveryAllowed", [&srv](bt::Node&, double) { return srv.admit_planning_recovery(); },
      bt_leaf_ports("PlanningRecoveryAllowed"));
}

// Planning a path to the goal and following it (a failure reports its outcome).
template <class FailWith>
void register_path_actions(bt::Factory& f, NavigationServer& srv, const FailWith& fail_with) {
  f.register_simple_action(
      "ComputePathToPose",
      [&srv, fail_with](bt::Node& self, double, bool) {
        const auto plan = srv.get_path(self.input<Pose2>("goal"));
        if (!plan.result.ok()) {
          fail_with(self, plan.result);
          return bt::Status::FAILURE;
        }
        self.set_output<Path>("path", plan.path);
        self.set_output<int>("error_code", 0);
        return bt::Status::SUCCESS;
      },
      {}, bt_leaf_ports("ComputePathToPose"));
  f.register_simple_action(
      "FollowPath",
      [&srv, fail_with](bt::Node& self, double, bool first) {
        const auto path = self.get_input<Path>("path");
        const ActionStep step = srv.exe_path(path.value_or(Path{}), first);
        if (step.state == ActionStep::State::FAILED) fail_with(self, step.result);
        return to_status(step);
      },
      [&srv](bt::Node&) { srv.stop(); }, bt_leaf_ports("FollowPath"));
}

// The recoveries and the stop.
void register_recoveries(bt::Factory& f, NavigationServer& srv) {
  f.register_simple_action(
      "BackUp",
      [&srv](bt::Node& self, double, bool first) {
        return to_status(srv.back_up(self.input<double>("distance_m"), self.input<double>("speed_mps"), first));
      },
      [&srv](bt::Node&) { srv.cancel_recovery(); }, bt_leaf_ports("BackUp"));
  f.register_simple_action(
      "RotateInPlace",
      [&srv](bt::Node& self, double, bool first) {
        return to_status(srv.rotate_in_place(self.input<double>("angle_rad"), first));
      },
      [&srv](bt::Node&) { srv.cancel_recovery(); }, bt_leaf_ports("RotateInPlace"));
  f.register_simple_action(
      "Wait",
      [&srv](bt::Node& self, double, bool first) {
        return to_status(srv.wait(self.input<double>("duration_s"), first));
      },
      [&srv](bt::Node&) { srv.cancel_recovery(); }, bt_leaf_ports("Wait"));
  f.register_simple_action(
      "ClearCostmaps",
      [&srv](bt::Node&, double, bool) { return srv.clear_costmaps().ok() ? bt::Status::SUCCESS : bt::Status::FAILURE; },
      {}, bt_leaf_ports("ClearCostmaps"));
  f.register_simple_action(
      "RelaxConstraints",
      [&srv](bt::Node&, double, bool) {
        return srv.relax_constraints().ok() ? bt::Status::SUCCESS : bt::Status::FAILURE;
      },
      {}, bt_leaf_ports("RelaxConstraints"));
  f.register_simple_action(
      "Stop",
      [&srv](bt::Node&, double, bool) {
        srv.stop();
        return bt::Status::SUCCESS;
      },
      {}, bt_leaf_ports("Stop"));
}

}  // namespace

void Navigator::register_leaves(bt::Factory& f) {
  NavigationServer& srv = server_;
  const auto fail_with = [this](bt::Node& self, const Result& r) {
    self.set_output<int>("error_code", static_cast<int>(code(r.outcome)));
    last_failure_ = r;
  };
  f.register_simple_condition(
      "SensorsAlive", [this](bt::Node&, double) { return sensors_alive(); }, bt_leaf_ports("SensorsAlive"));
  f.register_simple_condition(
      "IsLocalizationHealthy", [this](bt::Node&, double) { return localizer_.healthy(now_s_); },
      bt_leaf_ports("IsLocalizationHealthy"));
  register_server_conditions(f, srv, fail_with);
  register_path_actions(f, srv, fail_with);
  register_recoveries(f, srv);
}

}  // namespace bipednav::navigation
