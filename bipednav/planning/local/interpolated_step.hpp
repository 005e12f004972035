#pragma once

namespace bipednav::planning::local {

// A line-search sample: the step x, the cost there and its slope along the search direction
// (valid = false: the cost was not finite).
struct LineSearchSample {
  double x = 0.0, value = 0.0, slope = 0.0;
  bool valid = false;
};

// The line search's polynomial step (Ceres' InterpolatingPolynomialMinimizingStepSize with cubic
// interpolation): the minimiser over [lo, hi] of the polynomial through the samples' values and
// slopes (s0 at x = 0, the current sample and, when valid, the previous one). An invalid current
// sample halves its step, kept within [lo, hi].
double interpolated_step(const LineSearchSample& s0, const LineSearchSample& prev, const LineSearchSample& cur,
                         double lo, double hi);

}  // namespace bipednav::planning::local
