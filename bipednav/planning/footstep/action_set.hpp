#pragma once

#include <string>
#include <vector>

#include "bipednav/common/biped.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::planning::footstep {

enum class ActionKind { kPlanar, kTStep, kStepOver, kStepOnto, kStepDown };

const char* action_kind_name(ActionKind k);

// One discrete action (section V-A), written for a LEFT stance foot: the right (swing) foot
// lands at (dx, dy, dtheta) in the stance foot's frame. For a right stance foot the action is
// mirrored (dy and dtheta negated). [dz_min, dz_max] is the admissible height change (eq. 4).
// `peak_m` is the swing foot's clearance height, which shapes the action's inverse heightmap.
struct FootstepAction {
  std::string name;
  ActionKind kind = ActionKind::kPlanar;
  double dx_m = 0.0;
  double dy_m = 0.0;
  double dtheta_rad = 0.0;
  double dz_min_m = -0.01;
  double dz_max_m = 0.01;
  double duration_s = 0.5;
  double peak_m = 0.04;
};

// The body the whole-body check sweeps (common/biped.hpp), named in the planner's namespace.
using bipednav::BodyModel;

// A robot's footstep capabilities: its actions and its body, plus the terrain tolerances.
struct ActionSet {
  std::string robot;
  std::vector<FootstepAction> actions;
  BodyModel body;
  double flatness_threshold_m = 0.015;  // max - min height under a footprint (section V-B)
  double max_step_height_m = 0.07;      // Dijkstra heuristic: steeper edges are impassable

  void validate() const;
  // v_max of eq. 6: the largest body-centre displacement per second of any action.
  double fastest_speed_mps() const;
};

// How far the body centre (midway between the nominal feet) moves during action `a`.
double body_centre_displacement_m(const FootstepAction& a, double separation_m);

// Nao (section VI): 12 planar footsteps, the T-step, step-over (6 cm bars) and step-onto /
// step-down with dz in [-7, 7] cm: 16 actions per stance foot. The T-step that precedes the
// 3D actions on the real robot is folded into them (their duration includes it).
ActionSet nao_action_set();
// Digit-sized walker: the same structure scaled to a 1.6 m biped with longer, faster steps.
ActionSet digit_action_set();
// Nao's 12 planar footsteps only (the 2D baseline of section VII-A).
ActionSet planar_only(const ActionSet& set);
// By robot profile name: "nao" or "digit".
ActionSet action_set_for(const std::string& robot);

}  // namespace bipednav::planning::footstep
