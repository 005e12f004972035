#pragma once

#include <cstdint>

#include "bipednav/common/pose2.hpp"

namespace bipednav {

// A biped's feet and body, shared by the footstep planner (planning/footstep/) and the simulator's
// walker (sim/humanoid_walker.hpp).

enum class Foot : std::uint8_t { kLeft = 0, kRight = 1 };

inline Foot other(Foot f) { return f == Foot::kLeft ? Foot::kRight : Foot::kLeft; }
inline const char* foot_name(Foot f) { return f == Foot::kLeft ? "left" : "right"; }

// A placed foot: the sole's centre and heading in the map frame, its height, and which foot.
struct Footstep {
  Pose2 pose;
  double z_m = 0.0;
  Foot foot = Foot::kLeft;
};

// Geometry of the simple articulated body used for the whole-body check (metres; heights are
// measured from the stance sole). Boxes are centred between the feet unless stated.
struct BodyModel {
  double foot_length_m = 0.16;
  double foot_width_m = 0.09;
  double nominal_separation_m = 0.10;  // sole centre to sole centre
  double ankle_height_m = 0.04;
  double hip_height_m = 0.22;
  double leg_width_m = 0.06;
  double torso_depth_m = 0.10;
  double torso_width_m = 0.14;
  double torso_bottom_m = 0.20;
  double arm_offset_m = 0.12;  // lateral offset of each arm's centre from the body centre
  double arm_depth_m = 0.06;
  double arm_width_m = 0.05;
  double arm_bottom_m = 0.22;
  double height_m = 0.58;

  void validate() const;
};

}  // namespace bipednav
