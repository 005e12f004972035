#include "bipednav/localization/drift_metrics.hpp"

#include <cmath>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::localization {

Drift trajectory_drift(const std::vector<SE3>& truth, const std::vector<SE3>& estimate) {
  if (truth.empty() || truth.size() != estimate.size())
    throw Error("trajectory_drift: expected two non-empty trajectories of equal length (got " +
                std::to_string(truth.size()) + " and " + std::to_string(estimate.size()) + ")");
  Drift d;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    if (i > 0) d.distance_m += (truth[i].translation() - truth[i - 1].translation()).head<2>().norm();
    const double e = (estimate[i].translation() - truth[i].translation()).head<2>().norm();
    d.max_translation_error_m = std::max(d.max_translation_error_m, e);
  }
  const SE3& t = truth.back();
  const SE3& e = estimate.back();
  d.translation_error_m = (e.translation() - t.translation()).head<2>().norm();
  d.height_error_m = e.translation().z() - t.translation().z();
  d.yaw_error_deg = rad2deg(angle_diff(pose2_from_se3(e).theta, pose2_from_se3(t).theta));
  if (d.distance_m > 0.0) {
    d.translation_percent = 100.0 * d.translation_error_m / d.distance_m;
    d.yaw_deg_per_10m = std::abs(d.yaw_error_deg) * 10.0 / d.distance_m;
  }
  return d;
}

}  // namespace bipednav::localization
