#pragma once

#include <deque>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/twist.hpp"

namespace bipednav::control {

// Oscillation (MBF OSCILLATION): within the last window_s of simulated time the commanded
// forward or yaw velocity changed sign at least max_sign_flips times while the robot moved
// less than min_net_progress_m (the distance between the window's first and last pose).
// Speeds below sign_deadband (m/s or rad/s) carry no sign.
struct OscillationCheckerParams {
  double window_s = 5.0;
  int max_sign_flips = 4;
  double min_net_progress_m = 0.3;
  double sign_deadband = 0.02;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("window_s", window_s);
    v("max_sign_flips", max_sign_flips);
    v("min_net_progress_m", min_net_progress_m);
    v("sign_deadband", sign_deadband);
  }
};

// Sign changes in a sequence of speeds, ignoring entries with |v| < deadband.
int count_sign_flips(const std::deque<double>& speeds, double deadband);

class OscillationChecker {
 public:
  explicit OscillationChecker(const OscillationCheckerParams& params = {});

  // Feeds the command sent and the pose at now_s; true when the robot oscillates.
  // Non-finite commands count as zero; a non-finite pose or time going backwards throws Error.
  bool check(const Twist& cmd, const Pose2& pose, double now_s);
  void reset();
  int last_flips() const { return last_flips_; }

 private:
  struct Sample {
    double t_s;
    Pose2 pose;
  };
  OscillationCheckerParams params_;
  std::deque<Sample> samples_;
  std::deque<double> vx_, wz_;
  int last_flips_ = 0;
};

}  // namespace bipednav::control
