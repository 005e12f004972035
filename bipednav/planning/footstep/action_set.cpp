#include "bipednav/planning/footstep/action_set.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace bipednav::planning::footstep {

const char* action_kind_name(ActionKind k) {
  switch (k) {
    case ActionKind::kPlanar:
      return "planar";
    case ActionKind::kTStep:
      return "t_step";
    case ActionKind::kStepOver:
      return "step_over";
    case ActionKind::kStepOnto:
      return "step_onto";
    case ActionKind::kStepDown:
      return "step_down";
  }
  return "unknown";
}

void ActionSet::validate() const {
  require(!actions.empty(), "actions", "at least one action");
  body.validate();
  require(flatness_threshold_m > 0, "flatness_threshold_m", "> 0");
  require(max_step_height_m > 0, "max_step_height_m", "> 0");
  for (const auto& a : actions) {
    require(a.duration_s > 0, "actions[" + a.name + "].duration_s", "> 0");
    require(a.dz_min_m <= a.dz_max_m, "actions[" + a.name + "].dz_min_m", "<= dz_max_m");
    require(a.peak_m > 0, "actions[" + a.name + "].peak_m", "> 0");
    require(std::isfinite(a.dx_m) && std::isfinite(a.dy_m) && std::isfinite(a.dtheta_rad), "actions[" + a.name + "]",
            "finite displacements");
  }
}

double body_centre_displacement_m(const FootstepAction& a, double separation_m) {
  // Left stance at the origin: the body centre sits half a separation to its right before the
  // step and half a separation to the left of the landed right foot after it.
  const double c = std::cos(a.dtheta_rad), s = std::sin(a.dtheta_rad), h = separation_m / 2.0;
  return std::hypot(a.dx_m - s * h, a.dy_m + c * h + h);
}

double ActionSet::fastest_speed_mps() const {
  double v = 0.0;
  for (const auto& a : actions)
    v = std::max(v, body_centre_displacement_m(a, body.nominal_separation_m) / a.duration_s);
  return v;
}

namespace {

FootstepAction planar(const std::string& name, double dx, double dy, double dth, double duration, double peak) {
  return {name, ActionKind::kPlanar, dx, dy, dth, -0.01, 0.01, duration, peak};
}

// The 3D actions shared by both robots, scaled by the step length and clearance of each.
void add_3d_actions(ActionSet& s, double sep, double over_dx, double onto_dx, double max_dz, double over_peak,
                    double t_step_s, double over_s, double onto_s) {
  const double half_pi = std::numbers::pi / 2.0;
  const double foot_l = s.body.foot_length_m, foot_w = s.body.foot_width_m;
  // T-step: the swing foot is placed across the front of the stance foot (Fig. 4(b)).
  s.actions.push_back(
      {"t_step", ActionKind::kTStep, foot_l / 2 + foot_w / 2 + 0.01, -0.02, -half_pi, -0.01, 0.01, t_step_s, 0.04});
  s.actions.push_back(
      {"step_over", ActionKind::kStepOver, over_dx, -sep, 0.0, -0.01, 0.01, t_step_s + over_s, over_peak});
  s.actions.push_back(
      {"step_onto", ActionKind::kStepOnto, onto_dx, -sep, 0.0, 0.01, max_dz, t_step_s + onto_s, max_dz + 0.03});
  s.actions.push_back(
      {"step_down", ActionKind::kStepDown, onto_dx, -sep, 0.0, -max_dz, -0.01, t_step_s + onto_s, 0.04});
}

}  // namespace

ActionSet nao_action_set() {
  ActionSet s;
  s.robot = "nao";
  const double d = 0.5;  // one basic step of Nao's walking controller, seconds
  s.actions = {
      planar("fwd_8", 0.08, -0.10, 0.0, d, 0.04),           planar("fwd_4", 0.04, -0.10, 0.0, d, 0.04),
      planar("in_place", 0.0, -0.10, 0.0, d, 0.04),         planar("back_4", -0.04, -0.10, 0.0, d, 0.04),
      planar("side_out", 0.0, -0.16, 0.0, d, 0.04),         planar("diag_out", 0.06, -0.13, 0.0, d, 0.04),
      planar("fwd_turn_out", 0.04, -0.11, -0.2, d, 0.04),   planar("turn_out", 0.02, -0.12, -0.4, d, 0.04),
      planar("back_turn_out", -0.02, -0.12, -0.3, d, 0.04), planar("fwd_turn_in", 0.04, -0.10, 0.2, d, 0.04),
      planar("turn_in", 0.02, -0.12, 0.3, d, 0.04),         planar("long_out", 0.08, -0.12, -0.1, d, 0.04),
  };
  add_3d_actions(s, 0.10, 0.22, 0.18, 0.07, 0.08, 1.5, 4.0, 3.5);
  return s;
}

ActionSet digit_action_set() {
  ActionSet s;
  s.robot = "digit";
  BodyModel& b = s.body;
  b.foot_length_m = 0.22;
  b.foot_width_m = 0.12;
  b.nominal_separation_m = 0.26;
  b.ankle_height_m = 0.10;
  b.hip_height_m = 0.90;
  b.leg_width_m = 0.14;
  b.torso_depth_m = 0.30;
  b.torso_width_m = 0.40;
  b.torso_bottom_m = 0.85;
  b.arm_offset_m = 0.30;
  b.arm_depth_m = 0.14;
  b.arm_width_m = 0.12;
  b.arm_bottom_m = 0.80;
  b.height_m = 1.60;
  s.flatness_threshold_m = 0.03;
  s.max_step_height_m = 0.18;
  const double d = 0.4;
  s.actions = {
      planar("fwd_40", 0.40, -0.26, 0.0, d, 0.12),          planar("fwd_20", 0.20, -0.26, 0.0, d, 0.12),
      planar("in_place", 0.0, -0.26, 0.0, d, 0.12),         planar("back_15", -0.15, -0.26, 0.0, d, 0.12),
      planar("side_out", 0.0, -0.40, 0.0, d, 0.12),         planar("diag_out", 0.25, -0.32, 0.0, d, 0.12),
      planar("fwd_turn_out", 0.20, -0.28, -0.25, d, 0.12),  planar("turn_out", 0.05, -0.30, -0.45, d, 0.12),
      planar("back_turn_out", -0.05, -0.30, -0.3, d, 0.12), planar("fwd_turn_in", 0.20, -0.26, 0.25, d, 0.12),
      planar("turn_in", 0.05, -0.28, 0.35, d, 0.12),        planar("long_out", 0.40, -0.30, -0.1, d, 0.12),
  };
  add_3d_actions(s, 0.26, 0.55, 0.45, 0.18, 0.25, 1.0, 2.0, 2.0);
  return s;
}

ActionSet planar_only(const ActionSet& set) {
  ActionSet s = set;
  std::erase_if(s.actions, [](const FootstepAction& a) { return a.kind != ActionKind::kPlanar; });
  return s;
}

ActionSet action_set_for(const std::string& robot) {
  if (robot == "nao") return nao_action_set();
  if (robot == "digit") return digit_action_set();
  throw ParamError("robot", "a footstep robot profile: nao or digit (got '" + robot + "')");
}

}  // namespace bipednav::planning::footstep
