#pragma once

#include <cstdint>

#include "bipednav/common/pose2.hpp"

namespace bipednav::footstep {

enum class Foot : std::uint8_t { kLeft = 0, kRight = 1 };

inline Foot other(Foot f) { return f == Foot::kLeft ? Foot::kRight : Foot::kLeft; }
inline const char* foot_name(Foot f) { return f == Foot::kLeft ? "left" : "right"; }

// A placed foot: the sole's centre and heading in the map frame, its height, and which foot.
struct Footstep {
  Pose2 pose;
  double z_m = 0.0;
  Foot foot = Foot::kLeft;
};

// A planning state (x^, y^, theta^, f) of section V-A: the discretised pose of the stance foot.
struct StateKey {
  std::int32_t ix = 0;
  std::int32_t iy = 0;
  std::int32_t itheta = 0;
  Foot stance = Foot::kLeft;

  bool operator==(const StateKey&) const = default;
  std::uint64_t packed() const {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(ix) & 0xFFFFFu) << 44) |
           (static_cast<std::uint64_t>(static_cast<std::uint32_t>(iy) & 0xFFFFFu) << 24) |
           (static_cast<std::uint64_t>(static_cast<std::uint32_t>(itheta) & 0x7FFFFFu) << 1) |
           static_cast<std::uint64_t>(stance);
  }
};

}  // namespace bipednav::footstep
