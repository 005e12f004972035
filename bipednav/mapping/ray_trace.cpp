#include "bipednav/mapping/ray_trace.hpp"

#include <climits>
#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"
#include "bipednav/common/xyz4.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#define BIPEDNAV_RAY_CELLS_AVX2 1
#endif

namespace bipednav::mapping {

namespace {

// The tests of end_cells and point_cells for four points at a time (the scalar code's arithmetic).
struct CellQuery {
  Eigen::Vector3d origin;  // for the 3D range
  double range_sq;
  Eigen::Vector2d origin2, lo, hi;  // the 2D ray: inside [lo, hi] and shorter than sqrt(len_sq)
  double len_sq;
  bool unclipped_ok;  // false: no point gets a cell of its own (the miss code instead)
  const GridGeometry* g;
  std::int32_t miss;  // the code of a finite point in range without a cell
};

#if defined(BIPEDNAV_RAY_CELLS_AVX2)
// Only AVX2 (no FMA: the products and sums round as the scalar code's).
#define BIPEDNAV_RAY_AVX2 __attribute__((target("avx2")))
BIPEDNAV_RAY_AVX2 std::size_t ray_cells_avx2(const CellQuery& q, const Eigen::Vector3f* points, std::size_t n,
                                             std::int32_t* out) {
  if (n < 4) return 0;  // no full block (and points may be null when n == 0)
  const __m256d ox = _mm256_set1_pd(q.origin.x()), oy = _mm256_set1_pd(q.origin.y()), oz = _mm256_set1_pd(q.origin.z());
  const __m256d o2x = _mm256_set1_pd(q.origin2.x()), o2y = _mm256_set1_pd(q.origin2.y());
  const __m256d lox = _mm256_set1_pd(q.lo.x()), loy = _mm256_set1_pd(q.lo.y());
  const __m256d hix = _mm256_set1_pd(q.hi.x()), hiy = _mm256_set1_pd(q.hi.y());
  const __m256d range_sq = _mm256_set1_pd(q.range_sq), len_sq = _mm256_set1_pd(q.len_sq);
  const __m256d gx = _mm256_set1_pd(q.g->origin_x_m), gy = _mm256_set1_pd(q.g->origin_y_m);
  const __m256d res = _mm256_set1_pd(q.g->resolution_m), zero = _mm256_setzero_pd();
  const __m256d width = _mm256_set1_pd(q.g->width), height = _mm256_set1_pd(q.g->height);
  const __m256d ok = _mm256_castsi256_pd(_mm256_set1_epi64x(q.unclipped_ok ? -1 : 0));
  const __m128i no_cell = _mm_set1_epi32(kNoCell), miss = _mm_set1_epi32(q.miss);
  const float* xyz = points->data();
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const auto [xf, yf, zf] = xyz4::load(xyz + 3 * i);
    // p.allFinite(): x - x == 0 for each coordinate (false for an infinity or a NaN).
    const __m128 finite_f = _mm_and_ps(_mm_and_ps(_mm_cmpeq_ps(_mm_sub_ps(xf, xf), _mm_setzero_ps()),
                                                  _mm_cmpeq_ps(_mm_sub_ps(yf, yf), _mm_setzero_ps())),
                                       _mm_cmpeq_ps(_mm_sub_ps(zf, zf), _mm_setzero_ps()));
    const __m256d x = _mm256_cvtps_pd(xf), y = _mm256_cvtps_pd(yf), z = _mm256_cvtps_pd(zf);
    // (p.cast<double>() - origin).squaredNorm() > range_sq: Eigen sums (dx^2 + dy^2) + dz^2.
    const __m256d dx = _mm256_sub_pd(x, ox), dy = _mm256_sub_pd(y, oy), dz = _mm256_sub_pd(z, oz);
    const __m256d d2 =
        _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
    const __m128i skip =
        _mm_or_si128(_mm_xor_si128(_mm_castps_si128(finite_f), _mm_set1_epi32(-1)),
                     _mm256_cvtpd_epi32(_mm256_and_pd(_mm256_cmp_pd(d2, range_sq, _CMP_GT_OQ), _mm256_set1_pd(-1.0))));
    // unclipped_end: inside the box, shorter than the limit, then world_to_cell.
    const __m256d ex = _mm256_sub_pd(x, o2x), ey = _mm256_sub_pd(y, o2y);
    const __m256d len2 = _mm256_add_pd(_mm256_mul_pd(ex, ex), _mm256_mul_pd(ey, ey));
    __m256d fast = _mm256_and_pd(ok, _mm256_cmp_pd(len2, len_sq, _CMP_LT_OQ));
    fast = _mm256_and_pd(fast, _mm256_and_pd(_mm256_cmp_pd(x, lox, _CMP_GE_OQ), _mm256_cmp_pd(y, loy, _CMP_GE_OQ)));
    fast = _mm256_and_pd(fast, _mm256_and_pd(_mm256_cmp_pd(x, hix, _CMP_LE_OQ), _mm256_cmp_pd(y, hiy, _CMP_LE_OQ)));
    const __m256d fx = _mm256_floor_pd(_mm256_div_pd(_mm256_sub_pd(x, gx), res));
    const __m256d fy = _mm256_floor_pd(_mm256_div_pd(_mm256_sub_pd(y, gy), res));
    fast =
        _mm256_and_pd(fast, _mm256_and_pd(_mm256_cmp_pd(fx, zero, _CMP_GE_OQ), _mm256_cmp_pd(fx, width, _CMP_LT_OQ)));
    fast =
        _mm256_and_pd(fast, _mm256_and_pd(_mm256_cmp_pd(fy, zero, _CMP_GE_OQ), _mm256_cmp_pd(fy, height, _CMP_LT_OQ)));
    // The index in double is exact (below 2^31); lanes without a cell compute 0 here.
    const __m256d index = _mm256_and_pd(fast, _mm256_add_pd(_mm256_mul_pd(fy, width), fx));
    const __m128i cell = _mm256_cvttpd_epi32(index);
    const __m128i has_cell = _mm256_cvtpd_epi32(_mm256_and_pd(fast, _mm256_set1_pd(-1.0)));  // -1 / 0 per lane
    __m128i code = _mm_blendv_epi8(miss, cell, has_cell);
    code = _mm_blendv_epi8(code, no_cell, skip);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), code);
  }
  return i;
}
#undef BIPEDNAV_RAY_AVX2

bool ray_cells_cpu_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#endif

void require_int32_cells(const GridGeometry& g) {
  if (g.size() > static_cast<std::size_t>(INT32_MAX)) throw Error("ray trace: a grid of more than 2^31 - 1 cells");
}

// Each point's code: kNoCell when it is not finite or farther than sqrt(q.range_sq) from q.origin in 3D,
// otherwise cell_of(point); four at a time with AVX2 where the CPU has it (the same arithmetic).
template <typename CellOf>
void query_cells(const CellQuery& q, const Eigen::Vector3f* points, std::size_t n, std::int32_t* out, CellOf cell_of) {
  require_int32_cells(*q.g);
  std::size_t i = 0;
#if defined(BIPEDNAV_RAY_CELLS_AVX2)
  if (ray_cells_cpu_has_avx2()) i = ray_cells_avx2(q, points, n, out);
#endif
  for (; i < n; ++i) {
    const Eigen::Vector3f& p = points[i];
    const bool in_range = p.allFinite() && !((p.cast<double>() - q.origin).squaredNorm() > q.range_sq);
    out[i] = in_range ? cell_of(p) : kNoCell;
  }
}

}  // namespace

void point_cells(const GridGeometry& g, const Eigen::Vector3f* points, std::size_t n, const Eigen::Vector3d& origin,
                 double range_sq, std::int32_t* out) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const CellQuery q{origin, range_sq, origin.head<2>(), {-inf, -inf}, {inf, inf}, inf, true, &g, kNoCell};
  query_cells(q, points, n, out, [&](const Eigen::Vector3f& p) {
    const auto c = g.world_to_cell(p.x(), p.y());
    return c ? static_cast<std::int32_t>(g.index(*c)) : kNoCell;
  });
}

bool clip_segment(Eigen::Vector2d& a, Eigen::Vector2d& b, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const Eigen::Vector2d d = b - a;
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 2; ++k) {
    const double p[2] = {-d[k], d[k]};
    const double q[2] = {a[k] - lo[k], hi[k] - a[k]};
    for (int s = 0; s < 2; ++s) {
      if (p[s] == 0.0) {
        if (q[s] < 0.0) return false;
        continue;
      }
      const double t = q[s] / p[s];
      if (p[s] < 0.0) {
        if (t > t1) return false;
        t0 = std::max(t0, t);
      } else {
        if (t < t0) return false;
        t1 = std::min(t1, t);
      }
    }
  }
  // An end inside the box stays bit-identical (a0 + 1 * (b - a0) may round away from b, and the
  // caller compares the end to tell a clipped ray from one ending at its return).
  const Eigen::Vector2d a0 = a;
  if (t0 > 0.0) a = a0 + t0 * d;
  if (t1 < 1.0) b = a0 + t1 * d;
  return true;
}

std::optional<ClippedRay> clip_ray(const GridGeometry& g, const Eigen::Vector2d& origin, const Eigen::Vector2d& point,
                                   double max_length_m) {
  return RayClipper(g, origin, max_length_m).clip(point);
}

RayClipper::RayClipper(const GridGeometry& g, const Eigen::Vector2d& origin, double max_length_m)
    : g_(g), origin_(origin), max_length_m_(max_length_m), max_length_sq_(max_length_m * max_length_m * (1.0 - 1e-9)) {
  // Shrink the box by a hair so a clipped end never floors onto the cell past the last one.
  const double eps = 1e-6 * g.resolution_m;
  lo_ = {g.origin_x_m, g.origin_y_m};
  hi_ = {g.origin_x_m + g.size_x_m() - eps, g.origin_y_m + g.size_y_m() - eps};
  if (origin.allFinite()) start_ = g.world_to_cell(origin.x(), origin.y());
  origin_inside_ = start_ && inside(origin);
}

void RayClipper::end_cells(const Eigen::Vector3f* points, std::size_t n, const Eigen::Vector3d& origin, double range_sq,
                           std::int32_t* out) const {
  const CellQuery q{origin, range_sq, origin_, lo_, hi_, max_length_sq_, origin_inside_, &g_, kClipCell};
  query_cells(q, points, n, out, [&](const Eigen::Vector3f& p) {
    const auto end = unclipped_end(p.head<2>().cast<double>());
    return end ? static_cast<std::int32_t>(g_.index(*end)) : kClipCell;
  });
}

std::optional<ClippedRay> RayClipper::clip(const Eigen::Vector2d& point) const {
  if (!start_ || !point.allFinite()) return std::nullopt;
  // On the grid and shorter than the limit (with a margin for the square root's rounding):
  // the clipping below would leave the ray as it is.
  if (const auto end = unclipped_end(point)) return ClippedRay{*start_, *end, false};
  Eigen::Vector2d a = origin_, b = point;
  bool clipped = false;
  const double len = (b - a).norm();
  if (len > max_length_m_) {
    b = a + (b - a) * (max_length_m_ / len);
    clipped = true;
  }
  const Eigen::Vector2d b_before = b;
  if (!clip_segment(a, b, lo_, hi_)) return std::nullopt;
  if (b != b_before) clipped = true;
  const auto end = g_.world_to_cell(b.x(), b.y());
  if (!end) return std::nullopt;
  return ClippedRay{*start_, *end, clipped};
}

}  // namespace bipednav::mapping
