#pragma once

#include <optional>
#include <vector>

#include "bipednav/common/point_cloud.hpp"

namespace bipednav::perception {

// The firing time of each point of a sweep recorded without one, from its azimuth: a spinning
// LiDAR fires a column at each azimuth once per revolution, so the time since the sweep start is
//   t = period_s * (angle turned from start_azimuth_rad to the point's azimuth, in the direction
//       of rotation) / (2 pi),
// in [0, period_s). Clockwise (seen from above, z up, as Velodynes spin): the azimuth decreases
// with time. Without `start_azimuth_rad` the sweep starts at the first finite point's azimuth (a
// sweep stored in firing order starts there). A point less than 1e-6 rad before the start (the
// first column's other beams, with rounding) is put at t = 0 rather than a revolution later.
// Exact up to rounding where each point lies on its beam's ray (the error is ~1e-7 rad of azimuth,
// ~2e-9 s at 10 Hz); with the beams' horizontal offsets (a few cm on an HDL-64E) it grows as
// offset / range.
std::vector<float> times_from_azimuth(const PointCloud& sweep, double period_s, bool clockwise,
                                      std::optional<double> start_azimuth_rad = std::nullopt);

}  // namespace bipednav::perception
