#pragma once

// Four packed xyz float points (12 floats: x0 y0 z0 x1 | y1 z1 x2 y2 | z2 x3 y3 z3) split into their
// x, y and z lanes with SSE shuffles, for the AVX2 per-point loops (ray cells, voxel keys).

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>

namespace bipednav::xyz4 {

struct Lanes {
  __m128 x, y, z;
};

inline Lanes load(const float* p) {
  const __m128 a = _mm_loadu_ps(p), b = _mm_loadu_ps(p + 4), c = _mm_loadu_ps(p + 8);
  return {_mm_shuffle_ps(a, _mm_shuffle_ps(b, c, _MM_SHUFFLE(1, 0, 3, 2)), _MM_SHUFFLE(3, 0, 3, 0)),
          _mm_shuffle_ps(_mm_shuffle_ps(a, b, _MM_SHUFFLE(0, 0, 1, 1)), _mm_shuffle_ps(b, c, _MM_SHUFFLE(2, 2, 3, 3)),
                         _MM_SHUFFLE(2, 0, 2, 0)),
          _mm_shuffle_ps(_mm_shuffle_ps(a, b, _MM_SHUFFLE(1, 1, 2, 2)), _mm_shuffle_ps(c, c, _MM_SHUFFLE(3, 3, 0, 0)),
                         _MM_SHUFFLE(2, 0, 2, 0))};
}

}  // namespace bipednav::xyz4
#endif
