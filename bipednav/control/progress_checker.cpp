#include "bipednav/control/progress_checker.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::control {

void ProgressCheckerParams::validate() const {
  require(std::isfinite(required_movement_radius_m) && required_movement_radius_m > 0.0, "required_movement_radius_m",
          "> 0 m");
  require(std::isfinite(movement_time_allowance_s) && movement_time_allowance_s > 0.0, "movement_time_allowance_s",
          "> 0 s");
}

ProgressChecker::ProgressChecker(const ProgressCheckerParams& params) : params_(params) { params_.validate(); }

bool ProgressChecker::check(const Pose2& pose, double now_s) {
  if (!pose.is_finite() || !std::isfinite(now_s)) throw Error("ProgressChecker::check: pose or time is not finite");
  if (has_reference_ && now_s < last_s_) throw Error("ProgressChecker::check: time went backwards");
  last_s_ = now_s;
  if (!has_reference_ || distance(pose, reference_) >= params_.required_movement_radius_m) {
    has_reference_ = true;
    reference_ = pose;
    reference_s_ = now_s;
    return true;
  }
  return now_s - reference_s_ <= params_.movement_time_allowance_s;
}

}  // namespace bipednav::control
