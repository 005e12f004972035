#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace bipednav::planning::local {

// Cholesky factorisation and solve for a symmetric positive definite band matrix of half-bandwidth
// B, stored as its lower band: row i holds A(i, i - d) at i * (B + 1) + d, d = 0..B (the TEB
// solver's normal equations, teb_lm.cpp). B is a template parameter so the loops compile for the
// solver's fixed bandwidth.

// In place: on success `a` holds the factor L (same layout). Returns false if A is not positive
// definite. Only the envelope is worked on: row i of the factor is zero left of row i's first
// non-zero of A (first[i]), and skipping those exact zeros leaves every computed entry bit for bit
// as in the full band loop. Inactive penalties (velocity, acceleration) leave much of the band empty.
template <int B>
bool band_cholesky(std::vector<double>& a, std::size_t n, std::vector<std::size_t>& first) {
  constexpr std::size_t kW = B + 1;
  first.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t d = std::min<std::size_t>(B, i);
    while (d > 0 && a[i * kW + d] == 0.0) --d;
    first[i] = i - d;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j0 = first[i];
    for (std::size_t j = j0; j <= i; ++j) {
      double s = a[i * kW + (i - j)];
      for (std::size_t k = std::max(j0, first[j]); k < j; ++k) s -= a[i * kW + (i - k)] * a[j * kW + (j - k)];
      if (j == i) {
        if (!(s > 0.0) || !std::isfinite(s)) return false;
        a[i * kW] = std::sqrt(s);
      } else {
        a[i * kW + (i - j)] = s / a[j * kW];
      }
    }
  }
  return true;
}

// Solves L L^T y = b in place (y holds b on entry), L from band_cholesky.
template <int B>
void band_solve(const std::vector<double>& l, std::size_t n, std::vector<double>& y) {
  constexpr std::size_t kW = B + 1;
  for (std::size_t i = 0; i < n; ++i) {
    double s = y[i];
    const std::size_t j0 = i >= static_cast<std::size_t>(B) ? i - B : 0;
    for (std::size_t j = j0; j < i; ++j) s -= l[i * kW + (i - j)] * y[j];
    y[i] = s / l[i * kW];
  }
  for (std::size_t ii = n; ii-- > 0;) {
    double s = y[ii];
    const std::size_t j1 = std::min(n, ii + B + 1);
    for (std::size_t j = ii + 1; j < j1; ++j) s -= l[j * kW + (j - ii)] * y[j];
    y[ii] = s / l[ii * kW];
  }
}

}  // namespace bipednav::planning::local
