#include "bipednav/perception/ground_segmentation.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"

namespace bipednav::perception {

void RansacParams::validate() const {
  require(std::isfinite(distance_threshold_m) && distance_threshold_m > 0.0, "distance_threshold_m", "> 0 m");
  require(success_probability > 0.0 && success_probability < 1.0, "success_probability", "in (0, 1)");
  require(max_iterations >= 1, "max_iterations", ">= 1");
  require(prior_normal.allFinite() && prior_normal.norm() > 1e-9, "prior_normal", "a finite non-zero vector");
  require(max_points == 0 || max_points >= 3, "max_points", "0 (all points) or >= 3");
  require(max_normal_angle_rad >= 0.0 && max_normal_angle_rad <= M_PI, "max_normal_angle_rad", "in [0, pi]");
}

namespace {

// The finite points of `pts` (every `stride`-th point) into `s` (its buffers reused).
void finite_points(const std::vector<Eigen::Vector3f>& pts, SoaPoints& s, std::size_t stride = 1) {
  const std::size_t n = pts.size();
  const std::size_t cap = (n + stride - 1) / stride;
  for (auto* v : {&s.x, &s.y, &s.z}) v->resize(cap);
  s.index.resize(cap);
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; i += stride) {
    const Eigen::Vector3f& p = pts[i];
    s.x[m] = p.x();
    s.y[m] = p.y();
    s.z[m] = p.z();
    s.index[m] = i;
    m += p.allFinite() ? 1 : 0;
  }
  for (auto* v : {&s.x, &s.y, &s.z}) v->resize(m);
  s.index.resize(m);
}

// Number of points with D_i < t (eq. 4.2, 4.3). Counted in blocks; once even all remaining points
// could not reach `must_reach` the model cannot win and counting stops early (returns a lower bound).
// Eight lanes where the CPU has AVX2 (chosen at load time; the build targets baseline x86-64): the
// same float products and sums per point (AVX2 alone brings no fused multiply-add), the same count.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
std::size_t
count_inliers(const SoaPoints& s, const Plane& pl, float t, std::size_t must_reach = 0) {
  const float a = static_cast<float>(pl[0]), b = static_cast<float>(pl[1]), c = static_cast<float>(pl[2]),
              d = static_cast<float>(pl[3]);
  const float* x = s.x.data();
  const float* y = s.y.data();
  const float* z = s.z.data();
  const std::size_t n = s.size();
  constexpr std::size_t kBlock = 4096;
  std::size_t count = 0;
  for (std::size_t start = 0; start < n; start += kBlock) {
    const std::size_t end = std::min(n, start + kBlock);
    std::uint32_t block = 0;
    for (std::size_t i = start; i < end; ++i) block += std::fabs(a * x[i] + b * y[i] + c * z[i] + d) < t ? 1u : 0u;
    count += block;
    if (count + (n - end) < must_reach) return count;
  }
  return count;
}

double inlier_std(const SoaPoints& s, const Plane& pl, double t) {
  double sum = 0.0, sum2 = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double d = std::fabs(pl.head<3>().dot(s.at(i)) + pl[3]);
    if (d >= t) continue;
    sum += d;
    sum2 += d * d;
    ++n;
  }
  if (n == 0) return 0.0;
  const double mean = sum / static_cast<double>(n);
  return std::sqrt(std::max(0.0, sum2 / static_cast<double>(n) - mean * mean));
}

// eq. 4.4 with u the inlier ratio.
int required_iterations(double u, double rho, int cap) {
  const double good = u * u * u;
  if (good >= 1.0) return 1;
  if (good <= 0.0) return cap;
  const double n = std::round(std::log(1.0 - rho) / std::log(1.0 - good));
  return n >= cap ? cap : std::max(1, static_cast<int>(n));
}

bool passes_prior(const Plane& pl, const RansacParams& p, double cos_max) {
  return !p.use_normal_prior || std::fabs(pl.head<3>().dot(p.prior_normal.normalized())) >= cos_max;
}

// Plane through three sampled points, or nullopt-like (found = false) for a degenerate sample.
bool sample_plane(const SoaPoints& s, Rng& rng, Plane& out) {
  const auto n = static_cast<std::int64_t>(s.size());
  const auto i = static_cast<std::size_t>(rng.uniform_int(0, n - 1));
  std::size_t j = i, k = i;
  while (j == i) j = static_cast<std::size_t>(rng.uniform_int(0, n - 1));
  while (k == i || k == j) k = static_cast<std::size_t>(rng.uniform_int(0, n - 1));
  const Eigen::Vector3d p0 = s.at(i);
  const Eigen::Vector3d normal = (s.at(j) - p0).cross(s.at(k) - p0);
  const double len = normal.norm();
  if (!(len > 1e-12)) return false;
  out = normalize_plane(Plane(normal.x(), normal.y(), normal.z(), -normal.dot(p0)));  // eq. 4.1
  return true;
}

}  // namespace

Plane fit_plane_least_squares(const std::vector<Eigen::Vector3f>& points, const std::vector<std::size_t>& indices) {
  if (indices.size() < 3) return ground_plane_z0();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const std::size_t i : indices) mean += points[i].cast<double>();
  mean /= static_cast<double>(indices.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const std::size_t i : indices) {
    const Eigen::Vector3d d = points[i].cast<double>() - mean;
    cov.noalias() += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Eigen::Vector3d ev = eig.eigenvalues();
  if (!(ev[1] > 1e-12 * std::max(1.0, ev[2]))) return ground_plane_z0();  // collinear or a single point
  const Eigen::Vector3d normal = eig.eigenvectors().col(0);
  return normalize_plane(Plane(normal.x(), normal.y(), normal.z(), -normal.dot(mean)));
}

PlaneFit fit_plane_ransac(const std::vector<Eigen::Vector3f>& points, const RansacParams& params, Rng& rng,
                          RansacScratch* scratch) {
  params.validate();
  RansacScratch own;
  RansacScratch& w = scratch != nullptr ? *scratch : own;
  SoaPoints &buffers = w.sampled, &all = w.all;
  const std::size_t stride = params.max_points > 0 && points.size() > params.max_points
                                 ? (points.size() + params.max_points - 1) / params.max_points
                                 : 1;
  finite_points(points, buffers, stride);
  const SoaPoints& s = buffers;
  PlaneFit best;
  if (s.size() < 3) return best;
  const float t = static_cast<float>(params.distance_threshold_m);
  const double cos_max = std::cos(params.max_normal_angle_rad);
  int needed = params.max_iterations, degenerate = 0;
  double best_std = -1.0;  // computed lazily, only when a tie needs it
  while (best.iterations < needed && degenerate < 10 * params.max_iterations) {
    Plane pl;
    if (!sample_plane(s, rng, pl)) {
      ++degenerate;
      continue;
    }
    ++best.iterations;
    if (!passes_prior(pl, params, cos_max)) continue;
    const std::size_t count = count_inliers(s, pl, t, best.inliers);
    bool better = !best.found || count > best.inliers;
    if (!better && count == best.inliers) {
      if (best_std < 0.0) best_std = inlier_std(s, best.plane, t);
      const double sd = inlier_std(s, pl, t);
      better = sd < best_std;
      if (better) best_std = sd;
    } else if (better) {
      best_std = -1.0;
    }
    if (!better) continue;
    best.found = true;
    best.plane = pl;
    best.inliers = count;
    needed = required_iterations(static_cast<double>(count) / static_cast<double>(s.size()), params.success_probability,
                                 params.max_iterations);
  }
  if (!best.found) return best;
  if (params.refit) {
    std::vector<std::size_t>& in = w.refit;
    in.clear();
    for (std::size_t i = 0; i < s.size(); ++i)
      if (std::fabs(best.plane.head<3>().dot(s.at(i)) + best.plane[3]) < t) in.push_back(s.index[i]);
    const Plane refit = fit_plane_least_squares(points, in);
    const std::size_t refit_count = count_inliers(s, refit, t);
    // The refit must respect the prior and keep at least 95 % of the inliers (guards against a
    // refit tilted by a structure that crosses the inlier slab).
    if (20 * refit_count >= 19 * best.inliers && passes_prior(refit, params, cos_max)) {
      best.plane = refit;
      best.inliers = refit_count;
    }
  }
  if (stride > 1) {  // the result's counts are of all points
    finite_points(points, all);
    best.inliers = count_inliers(all, best.plane, t);
    if (params.inlier_std) best.inlier_std_m = inlier_std(all, best.plane, t);
    return best;
  }
  if (params.inlier_std) best.inlier_std_m = inlier_std(s, best.plane, t);
  return best;
}

}  // namespace bipednav::perception
