#pragma once

#include <cstdint>

#include "bipednav/common/biped.hpp"

namespace bipednav::planning::footstep {

// The walking body's feet (common/biped.hpp), named in the planner's namespace.
using bipednav::Foot;
using bipednav::foot_name;
using bipednav::Footstep;
using bipednav::other;

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

}  // namespace bipednav::planning::footstep
