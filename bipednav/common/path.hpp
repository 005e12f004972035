#pragma once

#include <string>
#include <vector>

#include "bipednav/common/pose2.hpp"

namespace bipednav {

// A sequence of planar poses in one frame, optionally timed (for local trajectories).
struct Path {
  std::string frame_id = "map";
  std::vector<Pose2> poses;
  std::vector<double> times_s;  // empty, or one time since the start per pose

  bool operator==(const Path&) const = default;
  bool empty() const { return poses.empty(); }
  std::size_t size() const { return poses.size(); }

  double length_m() const {
    double len = 0.0;
    for (std::size_t i = 1; i < poses.size(); ++i) len += distance(poses[i - 1], poses[i]);
    return len;
  }
};

}  // namespace bipednav
