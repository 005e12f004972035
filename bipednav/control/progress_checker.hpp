#pragma once

#include "bipednav/common/pose2.hpp"

namespace bipednav::control {

// The robot must move at least required_movement_radius_m away from where it was within
// movement_time_allowance_s of simulated time, else it is stuck (MBF ROBOT_STUCK). The
// radius should exceed a walker's sway so that swaying in place does not count as progress.
struct ProgressCheckerParams {
  double required_movement_radius_m = 0.5;
  double movement_time_allowance_s = 10.0;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("required_movement_radius_m", required_movement_radius_m);
    v("movement_time_allowance_s", movement_time_allowance_s);
  }
};

class ProgressChecker {
 public:
  explicit ProgressChecker(const ProgressCheckerParams& params = {});

  // Feeds the current pose at now_s; false when the robot is stuck. The first call (and the
  // first after reset()) sets the reference pose. Throws Error for non-finite input or time
  // going backwards.
  bool check(const Pose2& pose, double now_s);
  // Forgets the reference; call when control (re)starts or the robot is meant to stand still.
  void reset() { has_reference_ = false; }
  // Seconds since the robot last made progress (0 before the first check).
  double time_without_progress_s(double now_s) const { return has_reference_ ? now_s - reference_s_ : 0.0; }

 private:
  ProgressCheckerParams params_;
  bool has_reference_ = false;
  Pose2 reference_;
  double reference_s_ = 0.0;
  double last_s_ = 0.0;
};

}  // namespace bipednav::control
