#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace bipednav {

// A proportion's confidence interval.
struct Interval {
  double lo = 0.0, hi = 1.0;
};

// The Wilson score interval of k successes in n trials (Wilson 1927): unlike the normal
// approximation it stays inside [0, 1] and is not empty at k = 0 or k = n. z = 1.96 gives 95 %;
// n = 0 gives [0, 1] (nothing is known).
inline Interval wilson_interval(std::size_t k, std::size_t n, double z = 1.959963984540054) {
  if (n == 0) return {};
  const double nn = static_cast<double>(n), p = static_cast<double>(k) / nn, z2 = z * z;
  const double center = (p + z2 / (2.0 * nn)) / (1.0 + z2 / nn);
  const double half = z / (1.0 + z2 / nn) * std::sqrt(p * (1.0 - p) / nn + z2 / (4.0 * nn * nn));
  return {std::max(0.0, center - half), std::min(1.0, center + half)};
}

}  // namespace bipednav
