#include "bipednav/planning/local/moving_obstacles.hpp"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "bipednav/common/error.hpp"

namespace bipednav::planning::local {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

std::uint64_t cell_key(long x, long y) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) << 32) |
         static_cast<std::uint64_t>(static_cast<std::uint32_t>(y));
}

// Constant-velocity Kalman prediction of one axis over dt (white-noise acceleration of std q).
void kf_predict(double& p, double& v, Eigen::Matrix2d& P, double dt, double q) {
  p += v * dt;
  Eigen::Matrix2d F;
  F << 1.0, dt, 0.0, 1.0;
  Eigen::Matrix2d Q;
  const double q2 = q * q;
  Q << 0.25 * dt * dt * dt * dt * q2, 0.5 * dt * dt * dt * q2, 0.5 * dt * dt * dt * q2, dt * dt * q2;
  P = F * P * F.transpose() + Q;
}

// Kalman update of one axis with a position measurement z of variance r2.
void kf_update(double& p, double& v, Eigen::Matrix2d& P, double z, double r2) {
  const double s = P(0, 0) + r2;
  const Eigen::Vector2d k = P.col(0) / s;
  const double innov = z - p;
  p += k(0) * innov;
  v += k(1) * innov;
  Eigen::Matrix2d I_KH = Eigen::Matrix2d::Identity();
  I_KH(0, 0) -= k(0);
  I_KH(1, 0) -= k(1);
  P = I_KH * P;
}

}  // namespace

void MovingObstacleParams::validate() const {
  require(positive(cluster_cell_m), "moving_obstacles.cluster_cell_m", "> 0");
  require(min_points >= 1, "moving_obstacles.min_points", ">= 1");
  require(positive(max_blob_radius_m), "moving_obstacles.max_blob_radius_m", "> 0");
  require(positive(max_range_m), "moving_obstacles.max_range_m", "> 0");
  require(positive(gate_m), "moving_obstacles.gate_m", "> 0");
  require(positive(max_track_age_s), "moving_obstacles.max_track_age_s", "> 0");
  require(positive(measurement_noise_m), "moving_obstacles.measurement_noise_m", "> 0");
  require(positive(accel_noise_mps2), "moving_obstacles.accel_noise_mps2", "> 0");
  require(positive(max_speed_mps), "moving_obstacles.max_speed_mps", "> 0");
  require(min_hits >= 1, "moving_obstacles.min_hits", ">= 1");
  require(std::isfinite(min_moving_speed_mps) && min_moving_speed_mps >= 0.0, "moving_obstacles.min_moving_speed_mps",
          ">= 0");
  require(std::isfinite(min_displacement_m) && min_displacement_m >= 0.0, "moving_obstacles.min_displacement_m",
          ">= 0");
  require(std::isfinite(latch_displacement_m) && latch_displacement_m >= 0.0, "moving_obstacles.latch_displacement_m",
          ">= 0");
  require(positive(motion_window_s), "moving_obstacles.motion_window_s", "> 0");
  require(std::isfinite(moving_pause_s) && moving_pause_s >= 0.0, "moving_obstacles.moving_pause_s", ">= 0");
  require(positive(max_prediction_s), "moving_obstacles.max_prediction_s", "> 0");
  require(std::isfinite(global_map_margin_m) && global_map_margin_m >= 0.0, "moving_obstacles.global_map_margin_m",
          ">= 0");
  require(positive(max_coast_s), "moving_obstacles.max_coast_s", "> 0");
  require(std::isfinite(radius_floor_window_s) && radius_floor_window_s >= 0.0,
          "moving_obstacles.radius_floor_window_s", ">= 0");
  require(std::isfinite(reacquire_gate_m) && reacquire_gate_m >= 0.0, "moving_obstacles.reacquire_gate_m", ">= 0");
  require(std::isfinite(coast_max_growth_m) && coast_max_growth_m >= 0.0, "moving_obstacles.coast_max_growth_m",
          ">= 0");
  require(std::isfinite(structure_age_s) && structure_age_s >= 0.0, "moving_obstacles.structure_age_s", ">= 0");
  require(std::isfinite(structure_margin_m) && structure_margin_m >= 0.0, "moving_obstacles.structure_margin_m",
          ">= 0");
  require(positive(structure_min_fraction) && structure_min_fraction <= 1.0, "moving_obstacles.structure_min_fraction",
          "in (0, 1]");
}

void StaticStructure::update(const mapping::Costmap2D& occupancy, double stamp_s) {
  if (!std::isfinite(stamp_s) || stamp_s <= stamp_s_) return;
  const mapping::GridGeometry& g = occupancy.geometry();
  if (since_.size() != g.size() || g != geometry_) {
    geometry_ = g;
    since_.assign(g.size(), kInf);
  }
  const auto& cost = occupancy.data();
  for (std::size_t i = 0; i < since_.size(); ++i) {
    if (cost[i] != mapping::kLethal)
      since_[i] = kInf;
    else if (since_[i] == kInf)
      since_[i] = stamp_s;
  }
  stamp_s_ = stamp_s;
}

void StaticStructure::clear() {
  since_.clear();
  geometry_ = {};
  stamp_s_ = -1e300;
}

bool StaticStructure::near(const Eigen::Vector2d& p, double margin_m, double min_age_s) const {
  if (since_.empty() || !p.allFinite()) return false;
  const auto c = geometry_.world_to_cell_unbounded(p.x(), p.y());
  if (!c) return false;
  const int k = static_cast<int>(std::ceil(margin_m / geometry_.resolution_m - 1e-9));
  const double latest = stamp_s_ - min_age_s;
  for (int dy = -k; dy <= k; ++dy) {
    for (int dx = -k; dx <= k; ++dx) {
      const int x = c->x + dx, y = c->y + dy;
      if (geometry_.in_bounds(x, y) && since_[geometry_.index(x, y)] <= latest) return true;
    }
  }
  return false;
}

void SensorVisibilityParams::validate() const {
  require(std::isfinite(lidar_min_elevation_rad) && std::isfinite(lidar_max_elevation_rad) &&
              lidar_min_elevation_rad < lidar_max_elevation_rad,
          "sensor_visibility.lidar_min_elevation_rad", "finite and < lidar_max_elevation_rad");
  require(std::isfinite(lidar_min_range_m) && lidar_min_range_m >= 0.0 && lidar_min_range_m < lidar_max_range_m,
          "sensor_visibility.lidar_min_range_m", "in [0, lidar_max_range_m)");
  require(positive(depth_hfov_rad) && depth_hfov_rad < std::numbers::pi, "sensor_visibility.depth_hfov_rad",
          "in (0, pi)");
  require(positive(depth_vfov_rad) && depth_vfov_rad < std::numbers::pi, "sensor_visibility.depth_vfov_rad",
          "in (0, pi)");
  require(std::isfinite(depth_min_range_m) && depth_min_range_m >= 0.0 && depth_min_range_m < depth_max_range_m,
          "sensor_visibility.depth_min_range_m", "in [0, depth_max_range_m)");
  require(std::isfinite(min_obstacle_height_m) && min_obstacle_height_m >= 0.0,
          "sensor_visibility.min_obstacle_height_m", ">= 0");
}

SensorVisibility::SensorVisibility(const RobotProfile& robot, SensorVisibilityParams params)
    : params_(std::move(params)) {
  params_.validate();
  for (const auto& m : robot.sensors) {
    if (m.type == "vlp16") lidars_.emplace_back(m.x_m, m.y_m, m.z_m);
    if (m.type == "d430") cameras_.push_back(m.T_base_sensor().inverse());
  }
}

bool SensorVisibility::sees_base_point(const Eigen::Vector3d& p) const {
  if (!p.allFinite()) return false;
  for (const auto& o : lidars_) {
    const Eigen::Vector3d v = p - o;
    const double r = v.norm();
    const double elevation = std::atan2(v.z(), std::hypot(v.x(), v.y()));
    if (r >= params_.lidar_min_range_m && r <= params_.lidar_max_range_m &&
        elevation >= params_.lidar_min_elevation_rad && elevation <= params_.lidar_max_elevation_rad)
      return true;
  }
  const double th = std::tan(0.5 * params_.depth_hfov_rad), tv = std::tan(0.5 * params_.depth_vfov_rad);
  for (const auto& T : cameras_) {
    const Eigen::Vector3d q = T * p;  // x along the optical axis, y left, z up
    if (q.x() < params_.depth_min_range_m || q.norm() > params_.depth_max_range_m) continue;
    if (std::abs(q.y()) <= q.x() * th && std::abs(q.z()) <= q.x() * tv) return true;
  }
  return false;
}

bool SensorVisibility::sees(const Pose2& robot, const Eigen::Vector2d& p, double top_m) const {
  const Eigen::Vector2d b = robot.inverse().transform(p);
  // Samples of the segment from the lowest obstacle height to the top (the top alone decides for a
  // LiDAR looking down at it; a pitched camera may see only its lower part).
  constexpr int kSamples = 5;
  const double lo = std::min(params_.min_obstacle_height_m, top_m);
  for (int k = 0; k < kSamples; ++k) {
    const double z = lo + (top_m - lo) * k / (kSamples - 1);
    if (sees_base_point({b.x(), b.y(), z})) return true;
  }
  return false;
}

void DynamicAvoidanceParams::validate() const {
  require(positive(horizon_s), "dynamic_avoidance.horizon_s", "> 0");
  require(std::isfinite(robot_radius_m) && robot_radius_m >= 0.0, "dynamic_avoidance.robot_radius_m", ">= 0");
  require(std::isfinite(safety_margin_m) && safety_margin_m >= 0.0, "dynamic_avoidance.safety_margin_m", ">= 0");
  require(std::isfinite(prediction_growth_mps) && prediction_growth_mps >= 0.0,
          "dynamic_avoidance.prediction_growth_mps", ">= 0");
  require(positive(sim_step_s) && sim_step_s <= horizon_s, "dynamic_avoidance.sim_step_s", "in (0, horizon_s]");
  require(positive(static_check_s), "dynamic_avoidance.static_check_s", "> 0");
  // Holds between two rollout steps would repeat a candidate (the rollout brakes from a step on), and
  // a tiny step would make thousands of them on every control cycle.
  require(hold_step_s == 0.0 || (std::isfinite(hold_step_s) && hold_step_s >= sim_step_s),
          "dynamic_avoidance.hold_step_s", "0 (off) or >= sim_step_s");
}

namespace {

// cluster_blobs' binning of the points in range, four at a time: the same finite test, squared
// distance, quotient and floor as the scalar loop (IEEE division, subtraction, product and sum
// without contraction, and floor are exact operations: the lanes give the scalar's bits). A block
// whose kept bins do not fit an int32 is left to the scalar loop (returns its index).
#define BIPEDNAV_BLOB_AVX2 __attribute__((target("avx2")))
BIPEDNAV_BLOB_AVX2 std::size_t blob_bins_avx2(const Eigen::Vector2d* points, std::size_t n,
                                              const Eigen::Vector2d& center, double r2max, double cell, long* bx,
                                              long* by, std::size_t* kept, std::size_t& m) {
  static_assert(sizeof(Eigen::Vector2d) == 2 * sizeof(double));
  const __m256d cx = _mm256_set1_pd(center.x()), cy = _mm256_set1_pd(center.y());
  const __m256d r2 = _mm256_set1_pd(r2max), c = _mm256_set1_pd(cell), zero = _mm256_setzero_pd();
  const __m256d lo = _mm256_set1_pd(-2147483648.0), hi = _mm256_set1_pd(2147483647.0);
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const double* d = points[i].data();
    const __m256d a = _mm256_loadu_pd(d), b = _mm256_loadu_pd(d + 4);         // x0 y0 x1 y1 | x2 y2 x3 y3
    const __m256d x = _mm256_permute4x64_pd(_mm256_unpacklo_pd(a, b), 0xD8);  // x0 x1 x2 x3
    const __m256d y = _mm256_permute4x64_pd(_mm256_unpackhi_pd(a, b), 0xD8);
    // p.allFinite(): x - x and y - y are 0 (NaN for an infinity or a NaN).
    const __m256d finite = _mm256_and_pd(_mm256_cmp_pd(_mm256_sub_pd(x, x), zero, _CMP_EQ_OQ),
                                         _mm256_cmp_pd(_mm256_sub_pd(y, y), zero, _CMP_EQ_OQ));
    const __m256d dx = _mm256_sub_pd(x, cx), dy = _mm256_sub_pd(y, cy);
    const __m256d s = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
    const int keep = _mm256_movemask_pd(_mm256_and_pd(finite, _mm256_cmp_pd(s, r2, _CMP_NGT_UQ)));  // !(s > r2max)
    if (keep == 0) continue;
    const __m256d qx = _mm256_floor_pd(_mm256_div_pd(x, c)), qy = _mm256_floor_pd(_mm256_div_pd(y, c));
    const __m256d fits =
        _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(qx, lo, _CMP_GE_OQ), _mm256_cmp_pd(qx, hi, _CMP_LE_OQ)),
                      _mm256_and_pd(_mm256_cmp_pd(qy, lo, _CMP_GE_OQ), _mm256_cmp_pd(qy, hi, _CMP_LE_OQ)));
    if ((_mm256_movemask_pd(fits) & keep) != keep) return i;
    alignas(16) std::int32_t xi[4], yi[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(xi), _mm256_cvttpd_epi32(qx));
    _mm_store_si128(reinterpret_cast<__m128i*>(yi), _mm256_cvttpd_epi32(qy));
    for (int l = 0; l < 4; ++l) {
      if (!(keep & (1 << l))) continue;
      bx[m] = xi[l], by[m] = yi[l], kept[m] = i + static_cast<std::size_t>(l);
      ++m;
    }
  }
  return i;
}

bool blob_cpu_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

}  // namespace

std::vector<Blob> cluster_blobs(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& center,
                                const MovingObstacleParams& params, const std::vector<double>& heights,
                                const StaticStructure* structure, BlobScratch* scratch) {
  const bool check_structure = params.ignore_static_structure && structure != nullptr && !structure->empty();
  require(heights.empty() || heights.size() == points.size(), "cluster_blobs heights",
          "empty or one per point (" + std::to_string(points.size()) + "), got " + std::to_string(heights.size()));
  std::vector<Blob> out;
  const double cell = params.cluster_cell_m;
  const double r2max = params.max_range_m * params.max_range_m;
  BlobScratch own;
  BlobScratch& w = scratch != nullptr ? *scratch : own;
  // The bins of the points in range, in point order.
  std::vector<long>&bx = w.bx, &by = w.by;
  std::vector<std::size_t>& in_range = w.in_range;
  bx.resize(points.size());
  by.resize(points.size());
  in_range.resize(points.size());
  std::size_t m = 0, first = 0;
  if (blob_cpu_has_avx2())
    first = blob_bins_avx2(points.data(), points.size(), center, r2max, cell, bx.data(), by.data(), in_range.data(), m);
  for (std::size_t i = first; i < points.size(); ++i) {
    const Eigen::Vector2d& p = points[i];
    if (!p.allFinite() || (p - center).squaredNorm() > r2max) continue;
    bx[m] = static_cast<long>(std::floor(p.x() / cell)), by[m] = static_cast<long>(std::floor(p.y() / cell));
    in_range[m++] = i;
  }
  bx.resize(m);
  by.resize(m);
  in_range.resize(m);
  long x_lo = 0, x_hi = -1, y_lo = 0, y_hi = -1;
  if (m > 0) {
    x_lo = x_hi = bx[0], y_lo = y_hi = by[0];
    for (std::size_t k = 1; k < m; ++k)
      x_lo = std::min(x_lo, bx[k]), x_hi = std::max(x_hi, bx[k]), y_lo = std::min(y_lo, by[k]),
      y_hi = std::max(y_hi, by[k]);
  }
  if (in_range.empty()) return out;
  // Cells in a fixed order, (x, y) ascending, each a [begin, end) range of `order` (point indices,
  // ascending within a cell). The bins span a small window (max_range_m around the robot): a
  // counting sort over it; a hash of the bins when the window is too large for that.
  std::vector<std::size_t>& order = w.order;
  order.resize(in_range.size());
  std::vector<std::pair<std::size_t, std::size_t>>& cells = w.cells;
  std::vector<std::pair<long, long>>& cell_xy = w.cell_xy;
  cells.clear();
  cell_xy.clear();
  const auto span_x = static_cast<unsigned long>(x_hi - x_lo), span_y = static_cast<unsigned long>(y_hi - y_lo);
  const std::size_t grid_limit = std::max<std::size_t>(1 << 16, 8 * in_range.size());
  const bool dense = span_x < grid_limit && span_y < grid_limit && (span_x + 1) * (span_y + 1) <= grid_limit;
  const auto H = static_cast<std::size_t>(span_y + 1);
  std::vector<std::int32_t>& grid = w.grid;  // dense: cell index per bin, -1 when empty
  std::unordered_map<std::uint64_t, std::size_t> cell_of;
  if (dense) {
    const std::size_t W = static_cast<std::size_t>(span_x + 1);
    std::vector<std::uint32_t>& start = w.start;
    start.assign(W * H + 1, 0);
    const auto bin = [&](std::size_t k) {
      return static_cast<std::size_t>(bx[k] - x_lo) * H + static_cast<std::size_t>(by[k] - y_lo);
    };
    for (std::size_t k = 0; k < in_range.size(); ++k) ++start[bin(k) + 1];
    grid.assign(W * H, -1);
    for (std::size_t b = 0; b < W * H; ++b) {
      if (start[b + 1] > 0) {
        grid[b] = static_cast<std::int32_t>(cells.size());
        cells.emplace_back(start[b], start[b] + start[b + 1]);
        cell_xy.emplace_back(x_lo + static_cast<long>(b / H), y_lo + static_cast<long>(b % H));
      }
      start[b + 1] += start[b];
    }
    for (std::size_t k = 0; k < in_range.size(); ++k) order[start[bin(k)]++] = in_range[k];
  } else {
    std::vector<std::tuple<long, long, std::size_t>> binned(in_range.size());
    for (std::size_t k = 0; k < in_range.size(); ++k) binned[k] = {bx[k], by[k], in_range[k]};
    std::sort(binned.begin(), binned.end());
    for (std::size_t i = 0; i < binned.size();) {
      std::size_t j = i;
      while (j < binned.size() && std::get<0>(binned[j]) == std::get<0>(binned[i]) &&
             std::get<1>(binned[j]) == std::get<1>(binned[i]))
        ++j;
      cell_of.emplace(cell_key(std::get<0>(binned[i]), std::get<1>(binned[i])), cells.size());
      cells.emplace_back(i, j);
      cell_xy.emplace_back(std::get<0>(binned[i]), std::get<1>(binned[i]));
      i = j;
    }
    for (std::size_t k = 0; k < binned.size(); ++k) order[k] = std::get<2>(binned[k]);
  }
  // The cell at bin (x, y), or -1.
  const auto find_cell = [&](long x, long y) -> std::int64_t {
    if (dense) {
      if (x < x_lo || x > x_hi || y < y_lo || y > y_hi) return -1;
      return grid[static_cast<std::size_t>(x - x_lo) * H + static_cast<std::size_t>(y - y_lo)];
    }
    const auto it = cell_of.find(cell_key(x, y));
    return it == cell_of.end() ? -1 : static_cast<std::int64_t>(it->second);
  };
  std::vector<char>& seen = w.seen;
  seen.assign(cells.size(), 0);
  std::vector<std::size_t>&stack = w.stack, &members = w.members;
  for (std::size_t c0 = 0; c0 < cells.size(); ++c0) {
    if (seen[c0]) continue;
    seen[c0] = 1;
    stack.assign(1, c0);
    members.clear();
    while (!stack.empty()) {
      const std::size_t c = stack.back();
      stack.pop_back();
      members.push_back(c);
      const auto [cx, cy] = cell_xy[c];
      for (long dy = -1; dy <= 1; ++dy) {
        for (long dx = -1; dx <= 1; ++dx) {
          const std::int64_t n = find_cell(cx + dx, cy + dy);
          if (n >= 0 && !seen[static_cast<std::size_t>(n)])
            seen[static_cast<std::size_t>(n)] = 1, stack.push_back(static_cast<std::size_t>(n));
        }
      }
    }
    Blob b;
    for (const std::size_t c : members) {
      for (std::size_t k = cells[c].first; k < cells[c].second; ++k) {
        const std::size_t i = order[k];
        b.centroid += points[i];
        if (!heights.empty() && std::isfinite(heights[i])) b.top_m = std::max(b.top_m, heights[i]);
      }
      b.points += static_cast<int>(cells[c].second - cells[c].first);
    }
    b.centroid /= static_cast<double>(b.points);
    // The largest distance is the square root of the largest squared distance (the rounded square
    // root is monotonic): one square root per blob.
    double r2 = 0.0;
    for (const std::size_t c : members) {
      for (std::size_t k = cells[c].first; k < cells[c].second; ++k)
        r2 = std::max(r2, (points[order[k]] - b.centroid).squaredNorm());
    }
    b.radius_m = std::max(b.radius_m, std::sqrt(r2));
    if (b.points < params.min_points || b.radius_m > params.max_blob_radius_m) continue;
    if (check_structure) {
      // The share of the blob's binning cells (at their centres) on long-standing structure.
      std::size_t on = 0;
      for (const std::size_t c : members) {
        const Eigen::Vector2d q((static_cast<double>(cell_xy[c].first) + 0.5) * cell,
                                (static_cast<double>(cell_xy[c].second) + 0.5) * cell);
        if (structure->near(q, params.structure_margin_m, params.structure_age_s)) ++on;
      }
      if (static_cast<double>(on) >= params.structure_min_fraction * static_cast<double>(members.size())) continue;
    }
    out.push_back(b);
  }
  return out;
}

MovingObstacleTracker::MovingObstacleTracker(MovingObstacleParams params) : params_(std::move(params)) {
  params_.validate();
}

void MovingObstacleTracker::set_static_structure(const mapping::Costmap2D& occupancy, double stamp_s) {
  if (params_.enabled && params_.ignore_static_structure) structure_.update(occupancy, stamp_s);
}

void MovingObstacleTracker::clear() {
  tracks_.clear();
  lost_.clear();
  structure_.clear();
  last_stamp_s_ = -1e300;
}

void MovingObstacleTracker::update(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& robot,
                                   double stamp_s) {
  if (!params_.enabled || !std::isfinite(stamp_s) || !robot.allFinite()) return;
  update_blobs(cluster_blobs(points, robot, params_, {}, &structure_, &blob_scratch_), stamp_s);
}

void MovingObstacleTracker::update(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& heights,
                                   const Pose2& robot, double stamp_s) {
  if (!params_.enabled || !std::isfinite(stamp_s) || !robot.is_finite()) return;
  update_blobs(cluster_blobs(points, robot.position(), params_, heights, &structure_, &blob_scratch_), stamp_s, robot);
}

namespace {

double position_sigma(const TrackedObstacle& t) { return std::sqrt(std::max(t.cov_x(0, 0), t.cov_y(0, 0))); }

// How much a coasting track's radius (and gate) grows: its position std beyond the one it had when
// last seen, bounded.
double coast_growth(const TrackedObstacle& t, double max_growth_m) {
  if (!t.coasting) return 0.0;
  return std::clamp(position_sigma(t) - t.seen_sigma_m, 0.0, max_growth_m);
}

// The distance from p to the segment [a, b].
double point_segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

// radius_floor: the distance from p to the segment from where the lost track l was last seen to where it
// is predicted at stamp_s (at most max_prediction_s past its last update).
double lost_track_distance(const TrackedObstacle& l, const Eigen::Vector2d& p, double stamp_s,
                           double max_prediction_s) {
  const double dt = std::min(stamp_s - l.stamp_s, max_prediction_s);
  return point_segment_distance(p, l.predict(l.last_seen_s), l.position + l.velocity * dt);
}

// radius_floor: adds a blob's radius to t's recent radii, forgets those older than window_s and
// returns the largest left.
double floor_radius(TrackedObstacle& t, double radius_m, double stamp_s, double window_s) {
  auto& r = t.radii;
  r.push_back({stamp_s, radius_m});
  r.erase(r.begin(), std::find_if(r.begin(), r.end(), [&](const TrackedObstacle::RadiusSample& s) {
            return s.stamp_s >= stamp_s - window_s;
          }));
  double out = 0.0;
  for (const auto& s : r) out = std::max(out, s.radius_m);
  return out;
}

}  // namespace

bool MovingObstacleTracker::is_moving(const TrackedObstacle& t) const {
  if (params_.recent_motion) return t.moving;
  return t.hits >= params_.min_hits && t.velocity.norm() >= params_.min_moving_speed_mps &&
         (t.displaced || (t.position - t.origin).norm() >= params_.min_displacement_m);
}

void MovingObstacleTracker::update_motion(TrackedObstacle& t, double stamp_s) const {
  if (!params_.recent_motion) {
    const double latch = params_.latch_displacement_m;
    if (latch > 0.0 && !t.displaced && t.hits >= params_.min_hits &&
        t.velocity.norm() >= params_.min_moving_speed_mps && (t.position - t.origin).squaredNorm() >= latch * latch)
      t.displaced = true;
    return;
  }
  // The window's samples and the latest one before it (where the track was motion_window_s ago, or
  // when last seen before a longer gap).
  auto& recent = t.recent;
  recent.push_back({stamp_s, t.position});
  auto first_in = std::find_if(recent.begin(), recent.end(), [&](const TrackedObstacle::Sample& s) {
    return s.stamp_s >= stamp_s - params_.motion_window_s;
  });
  if (first_in != recent.begin()) recent.erase(recent.begin(), first_in - 1);
  // The farthest of them from the latest centroid: the recent travel.
  double travel2 = 0.0;
  for (const auto& s : recent) travel2 = std::max(travel2, (t.position - s.position).squaredNorm());
  const double d_min = params_.min_displacement_m;
  const bool fast = t.velocity.norm() >= params_.min_moving_speed_mps;
  if (fast || !t.moving) t.last_fast_s = stamp_s;
  const bool pausing = t.moving && stamp_s - t.last_fast_s <= params_.moving_pause_s;
  t.moving = t.hits >= params_.min_hits && travel2 >= d_min * d_min && (fast || pausing);
}

void MovingObstacleTracker::update_blobs(const std::vector<Blob>& blobs, double stamp_s,
                                         const std::optional<Pose2>& robot) {
  if (!params_.enabled || !std::isfinite(stamp_s) || stamp_s <= last_stamp_s_) return;
  last_stamp_s_ = stamp_s;
  const double q = params_.accel_noise_mps2;
  const double r2 = params_.measurement_noise_m * params_.measurement_noise_m;
  // Predict every track to this cycle.
  for (auto& t : tracks_) {
    const double dt = stamp_s - t.stamp_s;
    kf_predict(t.position.x(), t.velocity.x(), t.cov_x, dt, q);
    kf_predict(t.position.y(), t.velocity.y(), t.cov_y, dt, q);
    t.stamp_s = stamp_s;
  }
  // Gated nearest-neighbour association, closest pairs first.
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    for (std::size_t j = 0; j < blobs.size(); ++j) {
      if (!blobs[j].centroid.allFinite()) continue;
      const double d = (tracks_[i].position - blobs[j].centroid).norm();
      // A coasting track's gate widens with its uncertainty (it may have slowed or turned unseen).
      if (d <= params_.gate_m + coast_growth(tracks_[i], params_.coast_max_growth_m)) pairs.emplace_back(d, i, j);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<char> track_used(tracks_.size(), 0), blob_used(blobs.size(), 0);
  for (const auto& [d, i, j] : pairs) {
    if (track_used[i] || blob_used[j]) continue;
    track_used[i] = blob_used[j] = 1;
    auto& t = tracks_[i];
    double rj2 = r2;
    if (params_.partial_view_noise) {
      const double r = params_.measurement_noise_m + std::max(0.0, t.max_radius_m - blobs[j].radius_m);
      rj2 = r * r;
    }
    kf_update(t.position.x(), t.velocity.x(), t.cov_x, blobs[j].centroid.x(), rj2);
    kf_update(t.position.y(), t.velocity.y(), t.cov_y, blobs[j].centroid.y(), rj2);
    const double speed = t.velocity.norm();
    if (speed > params_.max_speed_mps) t.velocity *= params_.max_speed_mps / speed;
    t.max_radius_m = std::max(t.max_radius_m, blobs[j].radius_m);
    t.radius_m = params_.keep_largest_radius ? t.max_radius_m : blobs[j].radius_m;
    if (params_.radius_floor)
      t.radius_m = std::max(t.radius_m, floor_radius(t, blobs[j].radius_m, stamp_s, params_.radius_floor_window_s));
    t.top_m = std::max(t.top_m, blobs[j].top_m);
    ++t.hits;
    update_motion(t, stamp_s);
  }
  // Tracks not seen this cycle keep their prediction until they are too old; a moving one whose
  // prediction is where no sensor could see it coasts on (the sensors' silence says nothing).
  const bool can_coast = params_.coast_in_blind_zone && robot && robot->is_finite() && !visibility_.empty();
  std::vector<TrackedObstacle> kept;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    auto& t = tracks_[i];
    if (track_used[i]) {
      t.last_seen_s = stamp_s;
      t.coasting = false;
      t.seen_sigma_m = position_sigma(t);
    }
    const double unseen_s = stamp_s - t.last_seen_s;
    if (unseen_s <= params_.max_track_age_s) {
      kept.push_back(t);
      continue;
    }
    const bool was_moving = t.coasting || is_moving(t);
    const bool coasts = was_moving && can_coast && t.top_m > 0.0 && unseen_s <= params_.max_coast_s &&
                        !((t.position - robot->position()).norm() <= params_.max_range_m &&
                          visibility_.sees(*robot, t.position, t.top_m));
    if (!coasts) {
      // Dropped: with radius_floor a moving one is remembered for reacquisition.
      if (params_.radius_floor && was_moving) lost_.emplace_back(t, stamp_s);
      continue;
    }
    t.coasting = true;
    kept.push_back(t);
  }
  tracks_ = std::move(kept);
  if (params_.radius_floor) {
    std::erase_if(lost_, [&](const std::pair<TrackedObstacle, double>& l) {
      return stamp_s - l.first.last_seen_s > params_.max_coast_s;
    });
  }
  for (std::size_t j = 0; j < blobs.size(); ++j) {
    if (blob_used[j] || !blobs[j].centroid.allFinite()) continue;
    TrackedObstacle t;
    t.id = next_id_++;
    t.position = t.origin = blobs[j].centroid;
    if (params_.recent_motion) t.recent.push_back({stamp_s, t.position});
    t.radius_m = t.max_radius_m = blobs[j].radius_m;
    t.top_m = blobs[j].top_m;
    t.stamp_s = t.last_seen_s = stamp_s;
    t.hits = 1;
    const double v0 = 0.5 * params_.max_speed_mps;
    t.cov_x << r2, 0.0, 0.0, v0 * v0;
    t.cov_y = t.cov_x;
    t.seen_sigma_m = position_sigma(t);
    if (params_.radius_floor && params_.reacquire_coasting) {
      // The nearest coasting track whose last seen or predicted position is within the gate
      // continues (as a lost one does, below), unless a lost track is nearer.
      std::size_t best = tracks_.size();
      double best_d = kInf;
      for (std::size_t k = 0; k < tracks_.size(); ++k) {
        const TrackedObstacle& c = tracks_[k];
        if (!c.coasting) continue;
        const double d = point_segment_distance(blobs[j].centroid, c.predict(c.last_seen_s), c.position);
        if (d <= params_.reacquire_gate_m && d < best_d) best = k, best_d = d;
      }
      for (const auto& lost : lost_) {
        if (lost_track_distance(lost.first, blobs[j].centroid, stamp_s, params_.max_prediction_s) < best_d)
          best = tracks_.size();
      }
      if (best < tracks_.size()) {
        TrackedObstacle& c = tracks_[best];
        c.position = blobs[j].centroid;
        c.cov_x = t.cov_x;
        c.cov_y = t.cov_y;
        ++c.hits;
        c.max_radius_m = std::max(c.max_radius_m, blobs[j].radius_m);
        c.top_m = std::max(c.top_m, blobs[j].top_m);
        for (auto& r : c.radii) r.stamp_s = stamp_s;  // the floor restarts its window now
        c.radius_m = std::max(params_.keep_largest_radius ? c.max_radius_m : blobs[j].radius_m,
                              floor_radius(c, blobs[j].radius_m, stamp_s, params_.radius_floor_window_s));
        c.coasting = false;
        c.last_seen_s = stamp_s;
        c.seen_sigma_m = position_sigma(c);
        update_motion(c, stamp_s);
        continue;
      }
    }
    if (params_.radius_floor) {
      // The nearest lost track whose last seen or predicted position is within the gate (distance
      // to the segment between them) continues.
      std::size_t best = lost_.size();
      double best_d = kInf;
      for (std::size_t k = 0; k < lost_.size(); ++k) {
        const double d = lost_track_distance(lost_[k].first, blobs[j].centroid, stamp_s, params_.max_prediction_s);
        if (d <= params_.reacquire_gate_m && d < best_d) best = k, best_d = d;
      }
      if (best < lost_.size()) {
        const TrackedObstacle& l = lost_[best].first;
        t.id = l.id;
        t.origin = l.origin;
        t.displaced = l.displaced;
        t.hits = std::max(t.hits, l.hits);
        t.velocity = l.velocity;
        t.max_radius_m = std::max(t.max_radius_m, l.max_radius_m);
        t.top_m = std::max(t.top_m, l.top_m);
        t.radii = l.radii;
        for (auto& r : t.radii) r.stamp_s = stamp_s;  // the floor restarts its window now
        t.radius_m = std::max(t.radius_m, floor_radius(t, blobs[j].radius_m, stamp_s, params_.radius_floor_window_s));
        if (params_.recent_motion) {
          t.recent = l.recent;
          t.recent.push_back({stamp_s, t.position});
          t.moving = false;
          t.last_fast_s = stamp_s;
        }
        lost_.erase(lost_.begin() + static_cast<std::ptrdiff_t>(best));
      } else {
        t.radii.push_back({stamp_s, t.radius_m});
      }
    }
    tracks_.push_back(t);
  }
}

std::vector<TrackedObstacle> MovingObstacleTracker::moving(double now_s) const {
  std::vector<TrackedObstacle> out;
  for (const auto& t : tracks_) {
    if (!is_moving(t) || (!t.coasting && now_s - t.last_seen_s > params_.max_track_age_s)) continue;
    out.push_back(t);
    out.back().radius_m += coast_growth(t, params_.coast_max_growth_m);
  }
  return out;
}

namespace {

// Steps the velocity towards the target within the acceleration limits, then the pose.
struct Rollout {
  Pose2 pose;
  Twist vel;
};

void step(Rollout& r, const Twist& target, const CommandLimits& lim, double dt) {
  const double dv = std::clamp(target.linear_x - r.vel.linear_x, -lim.acc_lim_x_mps2 * dt, lim.acc_lim_x_mps2 * dt);
  const double dw =
      std::clamp(target.angular_z - r.vel.angular_z, -lim.acc_lim_theta_radps2 * dt, lim.acc_lim_theta_radps2 * dt);
  r.vel.linear_x += dv;
  r.vel.angular_z += dw;
  r.pose = r.pose * Pose2{r.vel.linear_x * dt, 0.0, r.vel.angular_z * dt};
}

// The rolled-out robot against the predictions: the first time within the horizon at which it is
// within reach of a moving obstacle while the two still close in (infinity: never), and the
// smallest distance minus reach over the horizon.
struct RolloutCheck {
  double ttc_s = kInf;
  double min_gap_m = kInf;
  // The time after which the rollout is in no swept corridor (0: never in one, infinity: still in
  // one at the horizon); only computed on request.
  double corridor_exit_s = 0.0;
};

RolloutCheck rollout_check(const Pose2& pose, const Twist& current, const Twist& target,
                           const std::vector<TrackedObstacle>& moving, const CommandLimits& lim, double now_s,
                           const DynamicAvoidanceParams& p, std::vector<Pose2>* arc, bool corridors = false,
                           const std::vector<double>* turns = nullptr, double hold_s = kInf) {
  // The prediction of obstacle i at now_s + dt: constant velocity, turned back at its turn time.
  const auto at = [&](std::size_t i, double dt) -> Eigen::Vector2d {
    const double tt = turns ? (*turns)[i] : kInf;
    if (dt <= tt) return moving[i].predict(now_s + dt);
    return moving[i].predict(now_s + tt) - moving[i].velocity * (dt - tt);
  };
  Rollout r{pose, current};
  std::vector<double> prev(moving.size());
  for (std::size_t i = 0; i < moving.size(); ++i) prev[i] = (at(i, 0.0) - pose.position()).norm();
  if (arc) arc->assign(1, pose);
  RolloutCheck out;
  const int n = static_cast<int>(std::ceil(p.horizon_s / p.sim_step_s - 1e-9));
  for (int k = 1; k <= n; ++k) {
    const double t = k * p.sim_step_s;
    step(r, t - p.sim_step_s < hold_s - 1e-9 ? target : Twist{}, lim, p.sim_step_s);  // then braking
    if (arc && t <= p.static_check_s + 1e-9) arc->push_back(r.pose);
    for (std::size_t i = 0; i < moving.size(); ++i) {
      const double d = (at(i, t) - r.pose.position()).norm();
      const double reach = p.robot_radius_m + moving[i].radius_m + p.safety_margin_m + p.prediction_growth_mps * t;
      out.min_gap_m = std::min(out.min_gap_m, d - reach);
      if (!std::isfinite(out.ttc_s) && d < reach && d < prev[i] - 1e-6) out.ttc_s = t;
      prev[i] = d;
      // Inside the obstacle's corridor: within reach of its predicted path over the next horizon.
      if (corridors && point_segment_distance(r.pose.position(), at(i, t), at(i, t + p.horizon_s)) < reach)
        out.corridor_exit_s = k == n ? kInf : t + p.sim_step_s;
    }
  }
  return out;
}

}  // namespace

double time_to_collision(const Pose2& pose, const Twist& cmd, const std::vector<TrackedObstacle>& moving, double now_s,
                         const DynamicAvoidanceParams& params) {
  // Instant velocity changes: unlimited acceleration.
  const CommandLimits lim{1e9, 1e9, 1e9, 1e9, 1e9};
  return rollout_check(pose, cmd, cmd, moving, lim, now_s, params, nullptr).ttc_s;
}

YieldDecision yield_to_moving_obstacles(const Twist& cmd, const Pose2& pose, const Twist& current,
                                        const std::vector<TrackedObstacle>& moving, const mapping::Costmap2D& costmap,
                                        const CommandLimits& lim, double period_s, double now_s,
                                        const DynamicAvoidanceParams& p) {
  YieldDecision out;
  out.cmd = out.target = cmd;
  out.ttc_s = kInf;
  if (moving.empty() || !pose.is_finite() || !cmd.is_finite()) return out;
  const Twist cur = current.is_finite() ? current : Twist{};
  // reverse_at_structure: when each obstacle's leading edge would reach a lethal cell.
  std::vector<double> turn_s;
  const std::vector<double>* turns = nullptr;
  if (p.reverse_at_structure) {
    const double res = costmap.resolution_m();
    for (const auto& m : moving) {
      double tt = kInf;
      const double speed = m.velocity.norm();
      if (speed > 1e-3) {
        const Eigen::Vector2d dir = m.velocity / speed, c = m.predict(now_s);
        const double reach_m = speed * (p.horizon_s + 1e-9) + m.radius_m;
        for (double s = m.radius_m + 2.0 * res; s <= reach_m; s += 0.5 * res) {
          const Eigen::Vector2d q = c + dir * s;
          const auto cell = costmap.geometry().world_to_cell(q.x(), q.y());
          if (cell && costmap.cost(*cell) == mapping::kLethal) {
            tt = std::max(0.0, (s - m.radius_m) / speed);
            break;
          }
        }
      }
      turn_s.push_back(tt);
    }
    turns = &turn_s;
  }
  out.ttc_s = rollout_check(pose, cur, cmd, moving, lim, now_s, p, nullptr, false, turns).ttc_s;
  if (!std::isfinite(out.ttc_s)) return out;

  // Candidates: the command slowed along its arc, then a coarse grid of forward, turning and
  // backing commands, each held over the horizon; with hold_step_s, when none of those is free, the
  // grid again, held for multiples of it and then braked to a stop (longest hold first, so of
  // equally good ones the longest wins).
  struct Candidate {
    Twist cmd;
    double hold_s = kInf;
  };
  std::vector<Candidate> cand;
  for (const double f : {0.75, 0.5, 0.25, 0.0}) cand.push_back({{f * cmd.linear_x, 0.0, f * cmd.angular_z}});
  cand.push_back({});
  const double vb = lim.max_vel_x_backwards_mps, vf = lim.max_vel_x_mps, wm = lim.max_vel_theta_radps;
  std::vector<double> holds{kInf};
  if (p.hold_step_s > 0.0)
    for (int k = static_cast<int>(std::ceil(p.static_check_s / p.hold_step_s - 1e-9)) - 1; k >= 1; --k)
      holds.push_back(k * p.hold_step_s);
  for (const double hold : holds) {
    for (const double v : {-vb, -0.5 * vb, 0.0, 0.5 * vf, vf}) {
      if (v == 0.0 && std::isfinite(hold)) continue;  // turning in place then stopping: the held turn decides
      for (const double w : {-0.6 * wm, -0.3 * wm, 0.0, 0.3 * wm, 0.6 * wm}) cand.push_back({{v, 0.0, w}, hold});
    }
  }
  const auto deviation = [&](const Twist& c) {
    return std::abs(c.linear_x - cmd.linear_x) / std::max(vf, 1e-3) +
           0.5 * std::abs(c.angular_z - cmd.angular_z) / std::max(wm, 1e-3) + (c.linear_x < 0.0 ? 0.5 : 0.0);
  };
  // A collision-free candidate (against the predictions and the costmap) closest to the command;
  // when there is none, the one that keeps the largest gap to the moving obstacles.
  // With exit_swept_corridor, among the ones run into, the one leaving the corridors soonest first.
  const Candidate* best = nullptr;
  bool best_free = false;
  double best_dev = kInf, best_gap = -kInf, best_exit = kInf, best_ttc = kInf;
  std::vector<Pose2> arc;
  for (const auto& c : cand) {
    if (std::isfinite(c.hold_s) && best_free) break;  // the held commands come first and one is free
    const RolloutCheck rc =
        rollout_check(pose, cur, c.cmd, moving, lim, now_s, p, &arc, p.exit_swept_corridor, turns, c.hold_s);
    if (!poses_feasible(arc, costmap)) continue;
    const bool free = !std::isfinite(rc.ttc_s);
    const double dev = deviation(c.cmd);
    const bool sooner = rc.corridor_exit_s < best_exit - 1e-9;
    const bool as_soon = !sooner && !(rc.corridor_exit_s > best_exit + 1e-9);
    const bool better_blocked =
        p.exit_swept_corridor ? sooner || (as_soon && rc.min_gap_m > best_gap) : rc.min_gap_m > best_gap;
    const bool better = best == nullptr || (free && !best_free) || (free && best_free && dev < best_dev) ||
                        (!free && !best_free && better_blocked);
    if (!better) continue;
    best = &c, best_free = free, best_dev = dev, best_gap = rc.min_gap_m, best_exit = rc.corridor_exit_s;
    best_ttc = rc.ttc_s;
  }
  out.modified = true;
  if (best == nullptr) {
    out.target = {};
    out.cmd = clamp_command({}, cur, lim, period_s);
    out.ttc_s = rollout_check(pose, cur, Twist{}, moving, lim, now_s, p, nullptr, false, turns).ttc_s;
    return out;
  }
  out.target = best->cmd;
  out.cmd = clamp_command(best->cmd, cur, lim, period_s);
  out.ttc_s = best_ttc;  // the corridors and the arc the loop also asked for do not change it
  return out;
}

}  // namespace bipednav::planning::local
