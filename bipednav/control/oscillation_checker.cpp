#include "bipednav/control/oscillation_checker.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::control {

void OscillationCheckerParams::validate() const {
  require(std::isfinite(window_s) && window_s > 0.0, "window_s", "> 0 s");
  require(max_sign_flips >= 1, "max_sign_flips", ">= 1");
  require(std::isfinite(min_net_progress_m) && min_net_progress_m >= 0.0, "min_net_progress_m", ">= 0 m");
  require(std::isfinite(sign_deadband) && sign_deadband >= 0.0, "sign_deadband", ">= 0");
}

int count_sign_flips(const std::deque<double>& speeds, double deadband) {
  int flips = 0;
  int last_sign = 0;
  for (const double v : speeds) {
    if (!(std::abs(v) >= deadband) || v == 0.0) continue;
    const int sign = v > 0.0 ? 1 : -1;
    if (last_sign != 0 && sign != last_sign) ++flips;
    last_sign = sign;
  }
  return flips;
}

OscillationChecker::OscillationChecker(const OscillationCheckerParams& params) : params_(params) { params_.validate(); }

void OscillationChecker::reset() {
  samples_.clear();
  vx_.clear();
  wz_.clear();
  last_flips_ = 0;
}

bool OscillationChecker::check(const Twist& cmd, const Pose2& pose, double now_s) {
  if (!pose.is_finite() || !std::isfinite(now_s)) throw Error("OscillationChecker::check: pose or time is not finite");
  if (!samples_.empty() && now_s < samples_.back().t_s) throw Error("OscillationChecker::check: time went backwards");
  samples_.push_back({now_s, pose});
  vx_.push_back(std::isfinite(cmd.linear_x) ? cmd.linear_x : 0.0);
  wz_.push_back(std::isfinite(cmd.angular_z) ? cmd.angular_z : 0.0);
  while (now_s - samples_.front().t_s > params_.window_s) {
    samples_.pop_front();
    vx_.pop_front();
    wz_.pop_front();
  }
  last_flips_ = std::max(count_sign_flips(vx_, params_.sign_deadband), count_sign_flips(wz_, params_.sign_deadband));
  const double progress = distance(samples_.front().pose, pose);
  return last_flips_ >= params_.max_sign_flips && progress < params_.min_net_progress_m;
}

}  // namespace bipednav::control
