#include "bipednav/tracking/motion_test.hpp"

#include <algorithm>
#include <cmath>

namespace bipednav::tracking {

WindowVelocity regression_velocity(std::span<const TimedPosition> samples) {
  WindowVelocity out;
  const auto n = static_cast<double>(samples.size());
  if (samples.size() < 3) return out;
  double t_mean = 0.0;
  Eigen::Vector2d p_mean = Eigen::Vector2d::Zero();
  for (const auto& s : samples) t_mean += s.t_s, p_mean += s.position;
  t_mean /= n, p_mean /= n;
  double stt = 0.0;
  Eigen::Vector2d stp = Eigen::Vector2d::Zero();
  for (const auto& s : samples) {
    const double dt = s.t_s - t_mean;
    stt += dt * dt, stp += dt * (s.position - p_mean);
  }
  if (!(stt > 0.0)) return out;
  out.velocity = stp / stt;
  double rss = 0.0;
  for (const auto& s : samples) rss += (s.position - p_mean - out.velocity * (s.t_s - t_mean)).squaredNorm();
  out.standard_error_mps = std::sqrt(rss / (2.0 * n - 4.0) / stt);
  out.samples = static_cast<int>(samples.size());
  out.span_s = samples.back().t_s - samples.front().t_s;
  return out;
}

}  // namespace bipednav::tracking
