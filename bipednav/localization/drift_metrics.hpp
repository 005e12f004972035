#pragma once

#include <vector>

#include "bipednav/common/se3.hpp"

namespace bipednav::localization {

// End-point drift of an estimated trajectory against ground truth (both in the same world frame,
// sampled at the same instants).
struct Drift {
  double distance_m = 0.0;           // path length of the ground truth
  double translation_error_m = 0.0;  // final planar (x, y) position error
  double translation_percent = 0.0;  // of the distance travelled
  double height_error_m = 0.0;       // final z error
  double yaw_error_deg = 0.0;        // final heading error
  double yaw_deg_per_10m = 0.0;
  double max_translation_error_m = 0.0;  // planar, over the whole run
};

// Throws Error when the two sequences differ in length or are empty.
Drift trajectory_drift(const std::vector<SE3>& truth, const std::vector<SE3>& estimate);

}  // namespace bipednav::localization
