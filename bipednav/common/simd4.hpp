#pragma once

// Four-lane float vectors (GCC/Clang vector extensions) for per-ray and per-point loops (the
// simulator's rays, depth decimation): lane-wise operators compile to single SSE instructions on
// any x86-64, and to NEON on ARM, where plain loops are not reliably vectorised (reductions,
// selects, divisions).

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace bipednav::simd4 {

using F4 = float __attribute__((vector_size(16)));
using I4 = std::int32_t __attribute__((vector_size(16)));  // comparison results: -1 (true) or 0

inline F4 load(const float* p) {
  F4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline void store(float* p, F4 v) { std::memcpy(p, &v, sizeof v); }
inline F4 splat(float x) { return F4{x, x, x, x}; }
inline F4 select(I4 mask, F4 a, F4 b) { return mask ? a : b; }
// a < b ? a : b, lane-wise (as std::min: the second operand when either is NaN).
inline F4 min(F4 a, F4 b) { return b < a ? b : a; }
inline F4 max(F4 a, F4 b) { return a < b ? b : a; }
inline float hmin(F4 v) { return std::min(std::min(v[0], v[1]), std::min(v[2], v[3])); }
inline float hmax(F4 v) { return std::max(std::max(v[0], v[1]), std::max(v[2], v[3])); }
inline bool any(I4 m) { return (m[0] | m[1] | m[2] | m[3]) != 0; }

// Lanes of (a, b) picked by indices 0-3 (a) and 4-7 (b).
template <int I0, int I1, int I2, int I3>
inline F4 shuffle(F4 a, F4 b) {
#if defined(__clang__)
  return __builtin_shufflevector(a, b, I0, I1, I2, I3);
#else
  return __builtin_shuffle(a, b, I4{I0, I1, I2, I3});
#endif
}

}  // namespace bipednav::simd4
