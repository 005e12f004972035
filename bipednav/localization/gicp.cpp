#include "bipednav/localization/gicp.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::localization {

namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

constexpr std::uint32_t kNoMatch = 0xffffffffu;

// Runs fn(begin, end, worker) over [0, n) split into `threads` contiguous chunks.
template <class Fn>
void parallel_chunks(std::size_t n, int threads, Fn fn) {
  const std::size_t t = static_cast<std::size_t>(std::max(1, threads));
  if (t == 1 || n < 1000) {
    fn(std::size_t{0}, n, std::size_t{0});
    return;
  }
  std::vector<std::thread> pool;
  for (std::size_t w = 0; w < t; ++w) pool.emplace_back(fn, n * w / t, n * (w + 1) / t, w);
  for (auto& th : pool) th.join();
}

// Plane covariance from the neighbours of one point: the eigenvalues of their scatter become
// (epsilon, 1, 1), i.e. I - (1 - epsilon) n n^T with n the normal (smallest eigenvector).
template <class PointAt>
Eigen::Matrix3f plane_covariance(std::size_t count, PointAt point_at, double epsilon) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t t = 0; t < count; ++t) mean += point_at(t).template cast<double>();
  mean /= static_cast<double>(std::max<std::size_t>(count, 1));
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (std::size_t t = 0; t < count; ++t) {
    const Eigen::Vector3d d = point_at(t).template cast<double>() - mean;
    C.noalias() += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(C);
  const Eigen::Vector3d n = es.eigenvectors().col(0);  // ascending eigenvalues: the normal
  return (Eigen::Matrix3d::Identity() - (1.0 - epsilon) * n * n.transpose()).cast<float>();
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d K;
  K << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return K;
}

struct Linearization {
  Matrix6d H = Matrix6d::Zero();
  Vector6d b = Vector6d::Zero();
  double sq_dist = 0.0;
  std::size_t matches = 0;
  void add(const Linearization& o) {
    H += o.H;
    b += o.b;
    sq_dist += o.sq_dist;
    matches += o.matches;
  }
};

// Normal equations of the plane-to-plane cost at T (left perturbation T <- exp(delta) T).
// `match` holds each source point's target correspondence of the previous iteration (kNoMatch when
// none): its distance at the new pose bounds the nearest-neighbour search, which stays exact.
Linearization linearize(const GicpCloud& source, const GicpCloud& target, const SE3& T, const GicpParams& p,
                        std::vector<std::uint32_t>& match) {
  const int threads = std::max(1, p.threads);
  std::vector<Linearization> parts(static_cast<std::size_t>(threads));
  const Eigen::Matrix3d R = T.linear();
  // The searches keep distances "< bound": the next float up keeps pairs at exactly the maximum.
  const float max_d2 = std::nextafter(static_cast<float>(p.max_correspondence_m * p.max_correspondence_m),
                                      std::numeric_limits<float>::infinity());
  parallel_chunks(source.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t w) {
    Linearization& L = parts[w];
    for (std::size_t i = begin; i < end; ++i) {
      const Eigen::Vector3d q = T * source.points[i].cast<double>();
      const Eigen::Vector3f qf = q.cast<float>();
      std::uint32_t j = 0;
      float d2 = 0.0f;
      bool found = false;
      if (match[i] != kNoMatch) {
        // A relative margin: nanoflann may round the same distance differently.
        const float prev = (target.points[match[i]] - qf).squaredNorm() * (1.0f + 1e-4f) + 1e-12f;
        if (prev < max_d2) found = target.index.nearest(qf, prev, j, d2);
      }
      if (!found && !target.index.nearest(qf, max_d2, j, d2)) {
        match[i] = kNoMatch;
        continue;
      }
      match[i] = j;
      const Eigen::Matrix3d RCs = R * source.covariances[i].cast<double>();
      Eigen::Matrix3d C = target.covariances[j].cast<double>();
      C.noalias() += RCs * R.transpose();
      const Eigen::Matrix3d M = C.inverse();
      const Eigen::Vector3d r = target.points[j].cast<double>() - q;
      // J = d r / d delta = [-I, S] with S = skew(q) (S^T = -S), so J^T M J = [[M, -M S], [., -S M S]]
      // and J^T M r = [-M r, (M r) x q]; the lower-left block is filled in by symmetry at the end.
      const Eigen::Matrix3d S = skew(q);
      const Eigen::Matrix3d MS = M * S;
      const Eigen::Vector3d Mr = M * r;
      L.H.topLeftCorner<3, 3>() += M;
      L.H.topRightCorner<3, 3>() -= MS;
      L.H.bottomRightCorner<3, 3>().noalias() -= S * MS;
      L.b.head<3>() -= Mr;
      L.b.tail<3>() += Mr.cross(q);
      L.sq_dist += d2;
      ++L.matches;
    }
  });
  Linearization total;
  for (const auto& part : parts) total.add(part);
  total.H.bottomLeftCorner<3, 3>() = total.H.topRightCorner<3, 3>().transpose();
  return total;
}

}  // namespace

void GicpParams::validate() const {
  require(covariance_neighbours >= 5 && covariance_neighbours <= 100, "covariance_neighbours", "in [5, 100]");
  require(covariance_epsilon > 0.0 && covariance_epsilon < 1.0, "covariance_epsilon", "in (0, 1)");
  require(max_correspondence_m > 0.0, "max_correspondence_m", "> 0");
  require(max_iterations >= 1, "max_iterations", ">= 1");
  require(converged_translation_m > 0.0 && converged_rotation_rad > 0.0, "converged_translation_m/rotation_rad", "> 0");
  require(lm_lambda >= 0.0, "lm_lambda", ">= 0");
  require(threads >= 1 && threads <= 256, "threads", "in [1, 256]");
}

std::vector<Eigen::Matrix3f> plane_covariances(const std::vector<Eigen::Vector3f>& points, const KdTree3f& tree, int k,
                                               double epsilon, int threads) {
  std::vector<Eigen::Matrix3f> covs(points.size());
  parallel_chunks(points.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    std::vector<std::uint32_t> idx(static_cast<std::size_t>(k));
    std::vector<float> d2(static_cast<std::size_t>(k));
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t n = tree.knn(points[i], static_cast<std::size_t>(k), idx.data(), d2.data());
      covs[i] = plane_covariance(
          n, [&](std::size_t t) { return tree.point(idx[t]); }, epsilon);
    }
  });
  return covs;
}

// Per point in the tree's leaf order: consecutive queries then touch the same tree nodes and points.
std::vector<Eigen::Matrix3f> plane_covariances(const GicpIndex& index, int k, double epsilon, int threads) {
  const std::size_t n = index.size(), kk = static_cast<std::size_t>(std::max(k, 1));
  std::vector<Eigen::Matrix3f> covs(n);
  if (n == 0) return covs;
  const std::vector<std::uint32_t>& order = index.leaf_order();
  parallel_chunks(n, threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    std::vector<std::uint32_t> idx(kk);
    std::vector<float> d2(kk);
    for (std::size_t j = begin; j < end; ++j) {
      const std::uint32_t i = order[j];
      const std::size_t m = index.knn(index.point(i), kk, idx.data(), d2.data());
      covs[i] = plane_covariance(
          m, [&](std::size_t t) { return index.point(idx[t]); }, epsilon);
    }
  });
  return covs;
}

GicpCloud prepare_gicp_cloud(const PointCloud& cloud, const GicpParams& p) {
  p.validate();
  GicpCloud out;
  out.points.reserve(cloud.size());
  for (const auto& q : cloud.points)
    if (q.allFinite()) out.points.push_back(q);
  out.index = GicpIndex(out.points);
  if (out.points.size() >= static_cast<std::size_t>(p.covariance_neighbours))
    out.covariances = plane_covariances(out.index, p.covariance_neighbours, p.covariance_epsilon, p.threads);
  return out;
}

GicpCloud transform_gicp_cloud(const GicpCloud& cloud, const SE3& T) {
  GicpCloud out;
  const Eigen::Matrix3f R = T.linear().cast<float>();
  const Eigen::Vector3f t = T.translation().cast<float>();
  out.points.reserve(cloud.size());
  for (const auto& q : cloud.points) out.points.push_back(R * q + t);
  out.covariances.reserve(cloud.covariances.size());
  for (const auto& C : cloud.covariances) out.covariances.push_back(R * C * R.transpose());
  out.index = GicpIndex(out.points);
  return out;
}

GicpResult gicp_align(const GicpCloud& source, const GicpCloud& target, const SE3& guess, const GicpParams& p) {
  p.validate();
  Stopwatch sw;
  const std::size_t min_points = static_cast<std::size_t>(p.covariance_neighbours);
  if (source.size() < min_points || target.size() < min_points || source.covariances.size() != source.size() ||
      target.covariances.size() != target.size() || target.index.size() != target.size())
    throw Error("GICP: source and target need at least " + std::to_string(min_points) + " finite points each (got " +
                std::to_string(source.size()) + " and " + std::to_string(target.size()) + ")");
  if (!guess.matrix().allFinite()) throw Error("GICP: the initial guess is not finite");
  GicpResult res;
  SE3 T = guess;
  std::vector<std::uint32_t> match(source.size(), kNoMatch);
  for (res.iterations = 1; res.iterations <= p.max_iterations; ++res.iterations) {
    const Linearization L = linearize(source, target, T, p, match);
    res.correspondences = L.matches;
    res.fitness = L.matches > 0 ? L.sq_dist / static_cast<double>(L.matches) : 0.0;
    if (L.matches < 6) break;
    Matrix6d A = L.H;
    A.diagonal() += p.lm_lambda * L.H.diagonal();
    const Vector6d delta = -A.ldlt().solve(L.b);
    if (!delta.allFinite()) break;
    Vector6d xi;  // se3_exp takes (rho, phi)
    xi << delta.head<3>(), delta.tail<3>();
    T = se3_exp(xi) * T;
    if (delta.head<3>().norm() < p.converged_translation_m && delta.tail<3>().norm() < p.converged_rotation_rad) {
      res.converged = true;
      break;
    }
  }
  res.iterations = std::min(res.iterations, p.max_iterations);
  res.T_target_source = T;
  res.time_ms = sw.elapsed_ms();
  return res;
}

GicpResult gicp_align(const PointCloud& source, const PointCloud& target, const SE3& guess, const GicpParams& p) {
  Stopwatch sw;
  const GicpCloud s = prepare_gicp_cloud(source, p);
  const GicpCloud t = prepare_gicp_cloud(target, p);
  GicpResult r = gicp_align(s, t, guess, p);
  r.time_ms = sw.elapsed_ms();
  return r;
}

PointCloud remove_ground(const PointCloud& cloud_sensor, const SE3& T_base_sensor, double band_m) {
  PointCloud out = cloud_sensor.empty_copy();
  out.reserve(cloud_sensor.size());
  for (std::size_t i = 0; i < cloud_sensor.size(); ++i) {
    const Eigen::Vector3f& q = cloud_sensor.points[i];
    if (!q.allFinite()) continue;
    if ((T_base_sensor * q.cast<double>()).z() >= band_m) out.push_back_from(cloud_sensor, i);
  }
  return out;
}

}  // namespace bipednav::localization
