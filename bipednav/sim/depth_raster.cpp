#include "bipednav/sim/depth_raster.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "bipednav/common/error.hpp"
#include "bipednav/common/simd4.hpp"

namespace bipednav::sim {
namespace {

constexpr float kFarDepth = std::numeric_limits<float>::infinity();
// Surfaces nearer than this along the optical axis are not drawn (a ray cast would return
// them, but they are far below any camera's minimum range).
constexpr double kNearM = 1e-6;

// The coefficients of one row of one triangle, as draw_triangle's four-lane loop splats them.
struct RasterRowCoeffs {
  float r0, r1, r2, rg, e0u, e1u, e2u, gu;
};

#if defined(__x86_64__) && defined(__GNUC__)
#define BIPEDNAV_RASTER_AVX2 1
using RasterF8 = float __attribute__((vector_size(32)));
using RasterI8 = std::int32_t __attribute__((vector_size(32)));
__attribute__((target("avx2"))) inline RasterF8 raster_splat8(float x) { return RasterF8{x, x, x, x, x, x, x, x}; }

bool raster_cpu_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

// draw_triangle's row loop eight pixels at a time (AVX) where the CPU has AVX2: lane for lane the
// same float operations as the four-lane loop (multiply, then add: no FMA, the target is not
// "fma"), so the same depths. Draws the four-pixel blocks from u (a multiple of 4) on while the
// next block also starts at or before `end`, two blocks at a time; returns the first block not drawn.
__attribute__((target("avx2"))) int raster_block_pairs_avx2(float* row, const float* su, int u, int end,
                                                            const RasterRowCoeffs& c) {
  const RasterF8 r0 = raster_splat8(c.r0), r1 = raster_splat8(c.r1), r2 = raster_splat8(c.r2), rg = raster_splat8(c.rg);
  const RasterF8 e0u = raster_splat8(c.e0u), e1u = raster_splat8(c.e1u), e2u = raster_splat8(c.e2u),
                 gu = raster_splat8(c.gu);
  const RasterF8 zero = raster_splat8(0.0f);
  for (; u + 4 <= end; u += 8) {
    RasterF8 s, old;
    std::memcpy(&s, su + u, sizeof s);
    std::memcpy(&old, row + u, sizeof old);
    const RasterF8 q = rg + gu * s;
    const RasterI8 in = (r0 + e0u * s >= zero) & (r1 + e1u * s >= zero) & (r2 + e2u * s >= zero) & (q > old);
    const RasterF8 out = in ? q : old;
    std::memcpy(row + u, &out, sizeof out);
  }
  return u;
}
#endif

}  // namespace

void RasterMesh::add(const TriangleSoup& soup, bool convex_solid) {
  const auto n = static_cast<std::uint32_t>(soup.triangles.size());
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  if (convex_solid && n > 0) {
    Eigen::AlignedBox3f bounds;
    for (const Eigen::Vector3f& v : soup.vertices) {
      bounds.extend(v);
      centroid += v.cast<double>();
    }
    centroid /= static_cast<double>(soup.vertices.size());
    solids.push_back(bounds);
  }
  for (std::uint32_t first = 0; first < n; first += kChunkTriangles) {
    Chunk chunk;
    chunk.first = static_cast<std::uint32_t>(size());
    chunk.count = std::min(kChunkTriangles, n - first);
    chunk.solid = convex_solid ? static_cast<std::int32_t>(solids.size()) - 1 : -1;
    Eigen::AlignedBox3f box;
    for (std::uint32_t i = first; i < first + chunk.count; ++i) {
      Eigen::Vector3i t = soup.triangles[i];
      const auto vertex = [&](int k) -> const Eigen::Vector3f& {
        return soup.vertices.at(static_cast<std::size_t>(t[k]));
      };
      if (convex_solid) {  // outward: the normal points away from the centroid
        const Eigen::Vector3d a = vertex(0).cast<double>(), b = vertex(1).cast<double>(), c = vertex(2).cast<double>();
        if ((b - a).cross(c - a).dot(a - centroid) < 0.0) std::swap(t[1], t[2]);
      }
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3f& p = vertex(k);
        box.extend(p);
        xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
      }
    }
    chunk.center = box.center();
    chunk.half_extent = 0.5f * box.sizes();
    chunks.push_back(chunk);
  }
}

DepthRasterizer::DepthRasterizer(std::vector<float> slope_u, std::vector<float> slope_v, float max_depth_m)
    : width_(static_cast<int>(slope_u.size())),
      height_(static_cast<int>(slope_v.size())),
      stride_((width_ + 3) / 4 * 4),
      su_(std::move(slope_u)),
      sv_(std::move(slope_v)),
      max_depth_m_(max_depth_m) {
  if (width_ < 1 || height_ < 1) throw Error("DepthRasterizer: empty image");
  // Padding lanes continue the pixel grid; they are drawn like pixels and never read.
  const float step = width_ > 1 ? su_[1] - su_[0] : -1.0f;
  for (int u = width_; u < stride_; ++u) su_.push_back(su_.back() + step);
  inv_depth_.resize(static_cast<std::size_t>(stride_) * static_cast<std::size_t>(height_));
}

// The pixel rays' bounding pyramid, to skip chunks that no pixel ray can meet.
struct DepthRasterizer::Frustum {
  double su_lo, su_hi, sv_lo, sv_hi, max_depth;
  // Conservative: false only if the box (camera frame, centre c, half extent e) is outside.
  bool may_see(const Eigen::Vector3d& c, const Eigen::Vector3d& e) const {
    if (c.x() + e.x() <= kNearM || c.x() - e.x() > max_depth) return false;
    // Outside a side plane y = s x when min over the box of +-(y - s x) > 0.
    if (c.y() - su_hi * c.x() - (e.y() + std::abs(su_hi) * e.x()) > 0) return false;
    if (su_lo * c.x() - c.y() - (e.y() + std::abs(su_lo) * e.x()) > 0) return false;
    if (c.z() - sv_hi * c.x() - (e.z() + std::abs(sv_hi) * e.x()) > 0) return false;
    if (sv_lo * c.x() - c.z() - (e.z() + std::abs(sv_lo) * e.x()) > 0) return false;
    return true;
  }
};

void DepthRasterizer::render(const RasterScene& scene, const SE3& T_world_camera) {
  clear(scene, T_world_camera.linear().cast<float>(), static_cast<float>(T_world_camera.translation().z()));
  const SE3 T_camera_world = T_world_camera.inverse();
  draw(scene.statics, T_camera_world);
  for (std::size_t i = 0; i < scene.actors.size(); ++i) draw(scene.actors[i], T_camera_world * scene.T_world_actor[i]);
}

void DepthRasterizer::depth_row(int v, float* out) const {
  using namespace simd4;
  const float* in = &inv_depth_[static_cast<std::size_t>(v) * static_cast<std::size_t>(stride_)];
  int u = 0;
  for (; u + 4 <= width_; u += 4) {
    const F4 q = load(in + u);
    store(out + u, select(q > 0.0f, splat(1.0f) / q, splat(kFarDepth)));
  }
  for (; u < width_; ++u) out[u] = in[u] > 0.0f ? 1.0f / in[u] : kFarDepth;
}

void DepthRasterizer::render(const RasterScene& scene, const SE3& T_world_camera, float* depth) {
  render(scene, T_world_camera);
  for (int v = 0; v < height_; ++v)
    depth_row(v, depth + static_cast<std::size_t>(v) * static_cast<std::size_t>(width_));
}

// Starts every pixel at the nearest analytic plane ahead, or at nothing (inverse depth 0).
void DepthRasterizer::clear(const RasterScene& scene, const Eigen::Matrix3f& R, float camera_z) {
  using namespace simd4;
  bool cleared = false;  // the first plane also clears (a plane behind, q < 0, is nothing: 0)
  for (const float z : scene.plane_z) {
    // Along pixel ray r = (1, su, sv), world height changes by (R row 2) . r per unit depth.
    const double dz = static_cast<double>(z) - static_cast<double>(camera_z);
    if (!(std::abs(dz) > 0.0)) continue;  // camera in the plane: the plane is seen edge-on
    const auto p0 = static_cast<float>(R(2, 0) / dz), p1 = static_cast<float>(R(2, 1) / dz),
               p2 = static_cast<float>(R(2, 2) / dz);
    for (int v = 0; v < height_; ++v) {
      float* row = &inv_depth_[static_cast<std::size_t>(v) * static_cast<std::size_t>(stride_)];
      const F4 base = splat(p0 + p2 * sv_[static_cast<std::size_t>(v)]);
      for (int u = 0; u < stride_; u += 4) {
        const F4 q = base + splat(p1) * load(&su_[static_cast<std::size_t>(u)]);
        store(row + u, max(cleared ? load(row + u) : splat(0.0f), q));
      }
    }
    cleared = true;
  }
  if (!cleared) std::fill(inv_depth_.begin(), inv_depth_.end(), 0.0f);
}

void DepthRasterizer::draw(const RasterMesh& mesh, const SE3& T_camera_mesh) {
  const Frustum frustum{std::min(su_.front(), su_[static_cast<std::size_t>(width_ - 1)]) - 1e-4,
                        std::max(su_.front(), su_[static_cast<std::size_t>(width_ - 1)]) + 1e-4,
                        std::min(sv_.front(), sv_.back()) - 1e-4, std::max(sv_.front(), sv_.back()) + 1e-4,
                        static_cast<double>(max_depth_m_) * 1.001 + 1e-3};
  const Eigen::Matrix3d R = T_camera_mesh.linear();
  const Eigen::Matrix3d R_abs = R.cwiseAbs();
  const Eigen::Vector3d t = T_camera_mesh.translation();
  const Eigen::Matrix3f Rf = R.cast<float>();
  const Eigen::Vector3f tf = t.cast<float>();
  // A camera outside a convex solid's bounds (by a margin) sees none of its back faces.
  const Eigen::Vector3f camera = (-R.transpose() * t).cast<float>();
  cull_back_.resize(mesh.solids.size());
  for (std::size_t i = 0; i < mesh.solids.size(); ++i) {
    const Eigen::AlignedBox3f& b = mesh.solids[i];
    const Eigen::Vector3f margin = Eigen::Vector3f::Constant(1e-3f) + 1e-5f * b.sizes();
    cull_back_[i] = !Eigen::AlignedBox3f(b.min() - margin, b.max() + margin).contains(camera);
  }
  for (const RasterMesh::Chunk& chunk : mesh.chunks) {
    const Eigen::Vector3d c = R * chunk.center.cast<double>() + t;
    const Eigen::Vector3d e = R_abs * chunk.half_extent.cast<double>() + Eigen::Vector3d::Constant(1e-5);
    if (!frustum.may_see(c, e)) continue;
    const bool cull = chunk.solid >= 0 && cull_back_[static_cast<std::size_t>(chunk.solid)];
    const float* p = &mesh.xyz[9 * static_cast<std::size_t>(chunk.first)];
    for (std::uint32_t i = 0; i < chunk.count; ++i, p += 9) {
      const Eigen::Vector3f a = Rf * Eigen::Vector3f(p[0], p[1], p[2]) + tf;
      const Eigen::Vector3f b = Rf * Eigen::Vector3f(p[3], p[4], p[5]) + tf;
      const Eigen::Vector3f cc = Rf * Eigen::Vector3f(p[6], p[7], p[8]) + tf;
      draw_triangle(a, b, cc, cull);
    }
  }
}

void DepthRasterizer::draw_triangle(const Eigen::Vector3f& af, const Eigen::Vector3f& bf, const Eigen::Vector3f& cf,
                                    bool cull_back) {
  const Eigen::Vector3d a = af.cast<double>(), b = bf.cast<double>(), c = cf.cast<double>();
  if (a.x() <= kNearM && b.x() <= kNearM && c.x() <= kNearM) return;
  const double far = max_depth_m_;
  if (a.x() > far && b.x() > far && c.x() > far) return;  // every pixel it covers is out of range
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double det = n.dot(a);  // det(a, b, c): 0 when the camera is in the triangle's plane
  if (!(std::abs(det) > 0.0) || !std::isfinite(det)) return;
  if (cull_back && det > 0.0) return;  // outward normal n, camera at the origin behind it: n . a > 0
  // Ray r hits the triangle ahead iff sign(det) * (p x q) . r >= 0 for its edges (p, q).
  const double s = det > 0.0 ? 1.0 : -1.0;
  const Eigen::Vector3f e0 = (s * a.cross(b)).cast<float>(), e1 = (s * b.cross(c)).cast<float>(),
                        e2 = (s * c.cross(a)).cast<float>();
  const Eigen::Vector3f g = (n / det).cast<float>();  // inverse depth along r = g . r

  // Pixel bounds of the part ahead of the near plane (vertices and edge crossings).
  const double su0 = su_[0], sv0 = sv_[0];
  const double du = width_ > 1 ? su_[1] - su0 : -1.0, dv = height_ > 1 ? sv_[1] - sv0 : -1.0;
  double u_lo = INFINITY, u_hi = -INFINITY, v_lo = INFINITY, v_hi = -INFINITY;
  auto extend = [&](const Eigen::Vector3d& q) {
    const double u = (q.y() / q.x() - su0) / du, v = (q.z() / q.x() - sv0) / dv;
    u_lo = std::min(u_lo, u), u_hi = std::max(u_hi, u), v_lo = std::min(v_lo, v), v_hi = std::max(v_hi, v);
  };
  const Eigen::Vector3d* vert[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d &p = *vert[k], &q = *vert[(k + 1) % 3];
    if (p.x() > kNearM) extend(p);
    if ((p.x() > kNearM) != (q.x() > kNearM)) extend(p + (kNearM - p.x()) / (q.x() - p.x()) * (q - p));
  }
  const double wmax = width_ - 1, hmax = height_ - 1;
  if (!(u_hi >= -1.0 && u_lo <= wmax + 1.0 && v_hi >= -1.0 && v_lo <= hmax + 1.0)) return;
  const int u0 = static_cast<int>(std::clamp(std::floor(u_lo) - 1.0, 0.0, wmax)) & ~3;
  const int u1 = static_cast<int>(std::clamp(std::ceil(u_hi) + 1.0, 0.0, wmax));
  const int v0 = static_cast<int>(std::clamp(std::floor(v_lo) - 1.0, 0.0, hmax));
  const int v1 = static_cast<int>(std::clamp(std::ceil(v_hi) + 1.0, 0.0, hmax));

  using namespace simd4;
  const double su_abs_max = std::max(std::abs(su0), std::abs(su0 + du * wmax));
  const F4 e0u = splat(e0.y()), e1u = splat(e1.y()), e2u = splat(e2.y()), gu = splat(g.y());
#if defined(BIPEDNAV_RASTER_AVX2)
  const bool avx2 = raster_cpu_has_avx2();
#endif
  for (int v = v0; v <= v1; ++v) {
    const float sv = sv_[static_cast<std::size_t>(v)];
    // Row terms first, then the column term: the same operations for a shared edge's two
    // triangles, whose coefficients are exact negatives, give exact negatives.
    const F4 r0 = splat(e0.x() + e0.z() * sv), r1 = splat(e1.x() + e1.z() * sv), r2 = splat(e2.x() + e2.z() * sv);
    const F4 rg = splat(g.x() + g.z() * sv);
    // The columns where all three edge functions can be >= 0, widened by a pixel and by the
    // float rounding of the edge functions; the exact per-pixel test below decides.
    double lo = u0, hi = u1;
    for (const auto& [r, e] : {std::pair{r0[0], e0.y()}, std::pair{r1[0], e1.y()}, std::pair{r2[0], e2.y()}}) {
      const double c = static_cast<double>(r) + static_cast<double>(e) * su0, m = static_cast<double>(e) * du;
      const double tol = 1e-6 * (std::abs(r) + std::abs(e) * su_abs_max);
      if (m > 0.0)
        lo = std::max(lo, (-c - tol) / m - 1.0);
      else if (m < 0.0)
        hi = std::min(hi, (-c - tol) / m + 1.0);
      else if (c < -tol)
        hi = -1.0;
    }
    if (!(lo <= hi)) continue;
    float* row = &inv_depth_[static_cast<std::size_t>(v) * static_cast<std::size_t>(stride_)];
    int u = static_cast<int>(lo) & ~3;
    const int end = static_cast<int>(hi);
#if defined(BIPEDNAV_RASTER_AVX2)
    if (avx2)  // su_ and the rows are padded to stride_: a pair's second block is inside them too
      u = raster_block_pairs_avx2(row, su_.data(), u, end, {r0[0], r1[0], r2[0], rg[0], e0.y(), e1.y(), e2.y(), g.y()});
#endif
    for (; u <= end; u += 4) {
      const F4 su = load(&su_[static_cast<std::size_t>(u)]);
      const F4 q = rg + gu * su, old = load(row + u);
      const I4 in = (r0 + e0u * su >= 0.0f) & (r1 + e1u * su >= 0.0f) & (r2 + e2u * su >= 0.0f) & (q > old);
      store(row + u, select(in, q, old));
    }
  }
}

}  // namespace bipednav::sim
