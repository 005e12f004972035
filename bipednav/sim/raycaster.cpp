#include "bipednav/sim/raycaster.hpp"

#include <embree3/rtcore.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <string>

#include "bipednav/common/error.hpp"
#include "bipednav/common/simd4.hpp"

namespace bipednav::sim {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

void check_device(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE)
    throw Error(std::string("Embree error ") + std::to_string(static_cast<int>(e)) + " in " + what);
}

// Adds the soup as one triangle geometry of `scene`.
void attach_triangles(RTCDevice device, RTCScene scene, const TriangleSoup& soup) {
  if (soup.triangles.empty()) return;
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), soup.vertices.size()));
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                             3 * sizeof(unsigned), soup.triangles.size()));
  check_device(device, "rtcSetNewGeometryBuffer");
  for (std::size_t i = 0; i < soup.vertices.size(); ++i)
    for (int k = 0; k < 3; ++k) v[3 * i + k] = soup.vertices[i][k];
  for (std::size_t i = 0; i < soup.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) idx[3 * i + k] = static_cast<unsigned>(soup.triangles[i][k]);
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
}

RTCScene new_scene(RTCDevice device, RTCSceneFlags flags, RTCBuildQuality quality) {
  RTCScene s = rtcNewScene(device);
  check_device(device, "rtcNewScene");
  rtcSetSceneFlags(s, flags);
  rtcSetSceneBuildQuality(s, quality);
  return s;
}

void set_instance_transform(RTCGeometry inst, const SE3& T) {
  float m[12];  // 3x4 column major
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 3; ++r) m[3 * c + r] = static_cast<float>(T.matrix()(r, c));
  rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, m);
  rtcCommitGeometry(inst);
}

// Height of an unbounded horizontal plane (ground, ceiling), which is intersected analytically:
// kept out of the BVH, it would make every node's bounds huge.
std::optional<double> horizontal_plane_z(const Geometry& g) {
  const auto* p = std::get_if<Plane>(&g.shape);
  if (!p || p->size_m.x() > 0 || p->size_m.y() > 0 || !(p->normal.norm() > 0)) return std::nullopt;
  const Eigen::Vector3d n = g.T_parent_shape.linear() * p->normal.normalized();
  if (std::abs(n.z()) < 1.0 - 1e-9) return std::nullopt;
  return g.T_parent_shape.translation().z();
}

// Closed convex surfaces: the rasteriser may skip their back faces.
bool is_convex_solid(const Shape& s) {
  return std::holds_alternative<Box>(s) || std::holds_alternative<Cylinder>(s) || std::holds_alternative<Sphere>(s);
}

}  // namespace

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene statics = nullptr;  // static triangles
  RTCScene movers = nullptr;   // instances of the actor scenes (null without actors)
  std::vector<RTCScene> actor_scenes;
  std::vector<RTCGeometry> actor_instances;
  std::vector<Actor> actors;
  std::vector<float> plane_z;         // unbounded horizontal planes
  Eigen::AlignedBox3f movers_bounds;  // world bounds of all actors now (empty without actors)
  RasterScene raster;                 // the same geometry for DepthRasterizer

  // True if the ray segment [0, tfar] can meet an actor (slab test against their bounds):
  // most rays and packets skip the actor scene entirely.
  bool may_hit_movers(const Eigen::Vector3f& o, const Eigen::Vector3f& d, float tfar) const {
    float t0 = 0.0f, t1 = tfar;
    for (int k = 0; k < 3; ++k) {
      const float inv = 1.0f / d[k];
      float a = (movers_bounds.min()[k] - o[k]) * inv, b = (movers_bounds.max()[k] - o[k]) * inv;
      if (a > b) std::swap(a, b);
      t0 = a > t0 ? a : t0;  // NaN (origin on a slab face, parallel ray) keeps the bound
      t1 = b < t1 ? b : t1;
    }
    return t0 <= t1;
  }

  // Conservative: false only if no segment [0, tfar] of the packet's rays can meet an actor.
  // A box around all segments is tested first; if it overlaps the actors' bounds, every ray
  // gets the slab test. All 16 lanes are tested (inactive lanes repeat ray 0).
  bool may_reach_movers(const RTCRay16& r) const {
    using namespace simd4;
    constexpr int W = RayPacket::kWidth;
    const float* org[3] = {r.org_x, r.org_y, r.org_z};
    const float* dir[3] = {r.dir_x, r.dir_y, r.dir_z};
    for (int k = 0; k < 3; ++k) {
      F4 lo = load(org[k]), hi = lo;
      for (int b = 0; b < W; b += 4) {
        const F4 o = load(org[k] + b), e = o + load(r.tfar + b) * load(dir[k] + b);
        lo = min(lo, min(o, e));
        hi = max(hi, max(o, e));
      }
      const float l = hmin(lo), h = hmax(hi);
      // A margin for rounding in the end points (relative to the coordinates' size).
      const float margin = 1e-4f * (1.0f + std::abs(l) + std::abs(h));
      if (h + margin < movers_bounds.min()[k] || l - margin > movers_bounds.max()[k]) return false;
    }
    for (int b = 0; b < W; b += 4) {
      F4 t0 = splat(0.0f), t1 = load(r.tfar + b);
      for (int k = 0; k < 3; ++k) {
        const F4 o = load(org[k] + b), inv = splat(1.0f) / load(dir[k] + b);
        const F4 a = (splat(movers_bounds.min()[k]) - o) * inv, c = (splat(movers_bounds.max()[k]) - o) * inv;
        // NaN (origin on a slab face, parallel ray) keeps the bound.
        t0 = select(min(a, c) > t0, min(a, c), t0);
        t1 = select(max(a, c) < t1, max(a, c), t1);
      }
      if (any(t0 <= t1)) return true;
    }
    return false;
  }

  // Distance to the nearest horizontal plane along the ray, +inf if none is ahead.
  float plane_hit(float oz, float dz) const {
    float best = kInf;
    for (float z : plane_z) {
      const float t = (z - oz) / dz;
      if (t >= 0.0f && t < best) best = t;
    }
    return best;
  }
  double time_s = std::numeric_limits<double>::quiet_NaN();

  ~Impl() {
    for (RTCGeometry g : actor_instances) rtcReleaseGeometry(g);
    for (RTCScene s : actor_scenes) rtcReleaseScene(s);
    if (movers) rtcReleaseScene(movers);
    if (statics) rtcReleaseScene(statics);
    if (device) rtcReleaseDevice(device);
  }
};

void RayCasterParams::validate() const {
  require(threads >= 1 && threads <= 256, "threads", "in [1, 256]");
  tessellation.validate();
}

RayCaster::RayCaster(const World& world, const RayCasterParams& params) : impl_(std::make_unique<Impl>()) {
  params.validate();
  Impl& d = *impl_;
  const std::string config = "threads=" + std::to_string(params.threads);
  d.device = rtcNewDevice(config.c_str());
  if (!d.device) throw Error("Embree: rtcNewDevice failed (" + config + ")");

  const RTCSceneFlags robust = RTC_SCENE_FLAG_ROBUST;  // watertight: no rays slip through shared edges
  d.statics = new_scene(d.device, robust, RTC_BUILD_QUALITY_HIGH);
  TriangleSoup soup;
  for (const Geometry& g : world.statics) {
    if (const auto z = horizontal_plane_z(g)) {
      d.plane_z.push_back(static_cast<float>(*z));
    } else {
      const TriangleSoup shape = tessellate(g, params.tessellation);
      d.raster.statics.add(shape, is_convex_solid(g.shape));
      soup.append(shape);
    }
  }
  d.raster.plane_z = d.plane_z;
  attach_triangles(d.device, d.statics, soup);
  rtcCommitScene(d.statics);
  check_device(d.device, "static scene");

  if (world.actors.empty()) return;
  // Statics are not instanced under a common top scene: a ray first traverses the static BVH,
  // then the small actor scene with tfar already cut to the static hit.
  d.actors = world.actors;
  d.movers = new_scene(d.device, static_cast<RTCSceneFlags>(RTC_SCENE_FLAG_DYNAMIC | RTC_SCENE_FLAG_ROBUST),
                       RTC_BUILD_QUALITY_LOW);
  for (const Actor& a : world.actors) {
    RTCScene s = new_scene(d.device, robust, RTC_BUILD_QUALITY_MEDIUM);
    TriangleSoup parts;
    RasterMesh& raster = d.raster.actors.emplace_back();
    for (const Geometry& g : a.parts) {
      const TriangleSoup part = tessellate(g, params.tessellation);
      raster.add(part, is_convex_solid(g.shape));
      parts.append(part);
    }
    attach_triangles(d.device, s, parts);
    rtcCommitScene(s);
    d.raster.T_world_actor.push_back(SE3::Identity());
    d.actor_scenes.push_back(s);
    RTCGeometry inst = rtcNewGeometry(d.device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(inst, s);
    set_instance_transform(inst, SE3::Identity());
    rtcAttachGeometry(d.movers, inst);
    d.actor_instances.push_back(inst);
  }
  check_device(d.device, "actor scenes");
  set_time(0.0);
}

RayCaster::~RayCaster() = default;
RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;

void RayCaster::set_time(double t_s) {
  Impl& d = *impl_;
  if (t_s == d.time_s) return;
  d.time_s = t_s;
  if (d.actors.empty()) return;
  for (std::size_t i = 0; i < d.actors.size(); ++i) {
    d.raster.T_world_actor[i] = d.actors[i].pose_at(t_s);
    set_instance_transform(d.actor_instances[i], d.raster.T_world_actor[i]);
  }
  rtcCommitScene(d.movers);
  RTCBounds b;
  rtcGetSceneBounds(d.movers, &b);
  d.movers_bounds = Eigen::AlignedBox3f(Eigen::Vector3f(b.lower_x, b.lower_y, b.lower_z),
                                        Eigen::Vector3f(b.upper_x, b.upper_y, b.upper_z));
  check_device(d.device, "set_time");
}

double RayCaster::time_s() const { return impl_->time_s; }
const RasterScene& RayCaster::raster_scene() const { return impl_->raster; }

float RayCaster::cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, float max_range_m) const {
  const double n = dir.norm();
  if (!(n > 0.0) || !origin.allFinite() || !std::isfinite(n)) throw Error("RayCaster::cast: non-finite or zero ray");
  const Eigen::Vector3d u = dir / n;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(origin.x());
  rh.ray.org_y = static_cast<float>(origin.y());
  rh.ray.org_z = static_cast<float>(origin.z());
  rh.ray.dir_x = static_cast<float>(u.x());
  rh.ray.dir_y = static_cast<float>(u.y());
  rh.ray.dir_z = static_cast<float>(u.z());
  rh.ray.tnear = 0.0f;
  const float plane = impl_->plane_hit(rh.ray.org_z, rh.ray.dir_z);
  rh.ray.tfar = std::min(max_range_m, plane);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->statics, &ctx, &rh);
  if (impl_->movers && impl_->may_hit_movers(origin.cast<float>(), u.cast<float>(), rh.ray.tfar))
    rtcIntersect1(impl_->movers, &ctx, &rh);  // only a closer hit replaces the static one
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) return rh.ray.tfar;
  return plane <= max_range_m ? plane : kInf;
}

void RayCaster::cast_packet(const RayPacket& p, float max_range_m, float* ranges, bool coherent) const {
  using namespace simd4;
  constexpr int W = RayPacket::kWidth;
  static_assert(W % 4 == 0);
  // Fields that are the same for every packet; Embree writes only tfar and the hit.
  struct Constants {
    alignas(64) int valid[W + 1][W];  // valid[n]: lanes [0, n) active
    alignas(64) unsigned id[W];
    Constants() {
      for (int n = 0; n <= W; ++n)
        for (int i = 0; i < W; ++i) valid[n][i] = i < n ? -1 : 0;
      for (int i = 0; i < W; ++i) id[i] = static_cast<unsigned>(i);
    }
  };
  static const Constants constants;
  const Impl& d = *impl_;
  const int n = std::clamp(p.count, 0, W);
  if (n == 0) return;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  if (coherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRayHit16 rh;
  std::memcpy(rh.ray.org_x, p.org_x, sizeof(p.org_x));
  std::memcpy(rh.ray.org_y, p.org_y, sizeof(p.org_y));
  std::memcpy(rh.ray.org_z, p.org_z, sizeof(p.org_z));
  std::memcpy(rh.ray.dir_x, p.dir_x, sizeof(p.dir_x));
  std::memcpy(rh.ray.dir_y, p.dir_y, sizeof(p.dir_y));
  std::memcpy(rh.ray.dir_z, p.dir_z, sizeof(p.dir_z));
  for (int i = n; i < W; ++i) {  // inactive lanes repeat ray 0: every lane holds a well-defined ray
    rh.ray.org_x[i] = p.org_x[0];
    rh.ray.org_y[i] = p.org_y[0];
    rh.ray.org_z[i] = p.org_z[0];
    rh.ray.dir_x[i] = p.dir_x[0];
    rh.ray.dir_y[i] = p.dir_y[0];
    rh.ray.dir_z[i] = p.dir_z[0];
  }
  std::memcpy(rh.ray.id, constants.id, sizeof(rh.ray.id));
  std::memset(rh.ray.tnear, 0, sizeof(rh.ray.tnear));
  std::memset(rh.ray.time, 0, sizeof(rh.ray.time));
  std::memset(rh.ray.flags, 0, sizeof(rh.ray.flags));
  std::memset(rh.ray.mask, 0xFF, sizeof(rh.ray.mask));
  static_assert(RTC_INVALID_GEOMETRY_ID == 0xFFFFFFFFu);
  std::memset(rh.hit.geomID, 0xFF, sizeof(rh.hit.geomID));
  std::memset(rh.hit.instID[0], 0xFF, sizeof(rh.hit.instID[0]));
  // The analytic horizontal planes cut tfar.
  alignas(64) float plane[W];
  const F4 inf = splat(kInf), max_range = splat(max_range_m);
  for (int b = 0; b < W; b += 4) {
    const F4 oz = load(rh.ray.org_z + b), dz = load(rh.ray.dir_z + b);
    F4 best = inf;
    for (const float z : d.plane_z) {
      const F4 t = (splat(z) - oz) / dz;
      best = select((t >= 0.0f) & (t < best), t, best);
    }
    store(plane + b, best);
    store(rh.ray.tfar + b, min(max_range, best));
  }
  rtcIntersect16(constants.valid[n], d.statics, &ctx, &rh);
  if (d.movers && d.may_reach_movers(rh.ray)) rtcIntersect16(constants.valid[n], d.movers, &ctx, &rh);
  alignas(64) float out[W];
  for (int b = 0; b < W; b += 4) {
    I4 geom;
    std::memcpy(&geom, rh.hit.geomID + b, sizeof geom);
    const F4 pl = load(plane + b);
    const F4 miss = select(pl <= max_range, pl, inf);
    store(out + b, select(geom != static_cast<std::int32_t>(RTC_INVALID_GEOMETRY_ID), load(rh.ray.tfar + b), miss));
  }
  std::memcpy(ranges, out, sizeof(float) * static_cast<std::size_t>(n));
}

void RayCaster::cast_batch(const Eigen::Vector3f& origin, const Eigen::Matrix3f& R,
                           std::span<const Eigen::Vector3f> unit_dirs, float max_range_m, std::span<float> ranges,
                           bool coherent) const {
  if (ranges.size() != unit_dirs.size()) throw Error("RayCaster::cast_batch: ranges and dirs differ in size");
  RayPacket p;
  for (int i = 0; i < RayPacket::kWidth; ++i) {
    p.org_x[i] = origin.x();
    p.org_y[i] = origin.y();
    p.org_z[i] = origin.z();
  }
  for (std::size_t base = 0; base < unit_dirs.size(); base += RayPacket::kWidth) {
    p.count = static_cast<int>(std::min<std::size_t>(RayPacket::kWidth, unit_dirs.size() - base));
    for (int i = 0; i < p.count; ++i) {
      const Eigen::Vector3f u = R * unit_dirs[base + static_cast<std::size_t>(i)];
      p.dir_x[i] = u.x();
      p.dir_y[i] = u.y();
      p.dir_z[i] = u.z();
    }
    cast_packet(p, max_range_m, &ranges[base], coherent);
  }
}

}  // namespace bipednav::sim
