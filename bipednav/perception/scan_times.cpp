#include "bipednav/perception/scan_times.hpp"

#include <cmath>
#include <numbers>

#include "bipednav/common/error.hpp"

namespace bipednav::perception {

std::vector<float> times_from_azimuth(const PointCloud& sweep, double period_s, bool clockwise,
                                      std::optional<double> start_azimuth_rad) {
  if (!(period_s > 0.0 && std::isfinite(period_s))) throw Error("times_from_azimuth: period_s must be > 0");
  if (start_azimuth_rad && !std::isfinite(*start_azimuth_rad))
    throw Error("times_from_azimuth: start_azimuth_rad must be finite");
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  constexpr double kSeamRad = 1e-6;
  std::vector<float> t(sweep.size(), 0.0f);
  std::optional<double> start = start_azimuth_rad;
  const double direction = clockwise ? -1.0 : 1.0;
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const Eigen::Vector3f& p = sweep.points[i];
    if (!p.allFinite()) continue;  // no azimuth: left at 0 (filters drop such points)
    const double az = std::atan2(static_cast<double>(p.y()), static_cast<double>(p.x()));
    if (!start) start = az;
    double turned = std::fmod(direction * (az - *start), kTwoPi);
    if (turned < 0.0) turned += kTwoPi;
    if (turned > kTwoPi - kSeamRad) turned = 0.0;
    t[i] = static_cast<float>(period_s * turned / kTwoPi);
  }
  return t;
}

}  // namespace bipednav::perception
