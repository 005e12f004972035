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

constexpr std::uint32_t kNoMatch = kGicpNoMatch;

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

// What the last search around a source point established, so later iterations can often prove
// the answer unchanged without searching: at `ref`, `first` (kNoMatch: none within the cap) was
// the nearest target point and every other one was at least `others` away.
struct MatchState {
  Eigen::Vector3f ref = Eigen::Vector3f::Zero();
  std::uint32_t first = kNoMatch, second = kNoMatch;
  float others = -1.0f;  // < 0: no search yet
};

// The exact nearest target point of q if closer than max_d (squared: max_d2), writing its index
// and squared distance. Once q has moved by `moved` from the last search, every point but `first`
// is at least others - moved away, so `first` stays the nearest while it is closer than that.
// Otherwise the two nearest within `cap` are searched, bounded by the previous two's distances.
bool find_match(const GicpIndex& target, const Eigen::Vector3f& q, float max_d, float max_d2, float cap, MatchState& s,
                std::uint32_t& j, float& d2) {
  constexpr float kMargin = 1e-5f;  // absorbs float rounding; a tie then costs only a search
  if (s.others >= 0.0f) {
    const float lower = s.others - (q - s.ref).norm() - kMargin * (1.0f + s.others);
    if (s.first == kNoMatch) {
      if (lower >= max_d) return false;
    } else {
      d2 = (target.point(s.first) - q).squaredNorm();
      if (std::sqrt(d2) <= lower) {
        j = s.first;
        return d2 < max_d2;
      }
    }
  }
  const float cap2 = cap * cap;
  float bound = cap2;
  if (s.first != kNoMatch && s.second != kNoMatch)
    bound =
        std::min(cap2, std::max((target.point(s.first) - q).squaredNorm(), (target.point(s.second) - q).squaredNorm()) *
                               (1.0f + 1e-4f) +
                           1e-12f);
  std::uint32_t idx[2];
  float sq[2];
  std::size_t m = target.knn(q, 2, idx, sq, bound);
  if (m < 2 && bound < cap2) m = target.knn(q, 2, idx, sq, cap2);
  s.ref = q;
  s.first = m > 0 ? idx[0] : kNoMatch;
  s.second = m > 1 ? idx[1] : kNoMatch;
  s.others = m > 1 ? std::sqrt(sq[1]) : cap;
  if (m == 0) return false;
  j = idx[0];
  d2 = sq[0];
  return d2 < max_d2;
}

// The correspondence search's distances: pairs are kept up to max_d (squared: max_d2, "<" the next
// float up); searching a little beyond the maximum (cap) lets unmatched points skip too.
struct MatchBounds {
  float max_d, max_d2, cap;
  explicit MatchBounds(const GicpParams& p)
      : max_d(static_cast<float>(p.max_correspondence_m)),
        max_d2(std::nextafter(max_d * max_d, std::numeric_limits<float>::infinity())),
        cap(1.1f * max_d) {}
};

// Normal equations of the plane-to-plane cost at T (left perturbation T <- exp(delta) T), with
// exact nearest-neighbour correspondences found through `state` (one per source point).
Linearization linearize(const GicpCloud& source, const GicpCloud& target, const SE3& T, const GicpParams& p,
                        std::vector<MatchState>& state) {
  const int threads = std::max(1, p.threads);
  std::vector<Linearization> parts(static_cast<std::size_t>(threads));
  const Eigen::Matrix3d R = T.linear();
  const MatchBounds b(p);
  parallel_chunks(source.size(), threads, [&](std::size_t begin, std::size_t end, std::size_t w) {
    Linearization& L = parts[w];
    for (std::size_t i = begin; i < end; ++i) {
      const Eigen::Vector3d q = T * source.points[i].cast<double>();
      std::uint32_t j = 0;
      float d2 = 0.0f;
      if (!find_match(target.index, q.cast<float>(), b.max_d, b.max_d2, b.cap, state[i], j, d2)) continue;
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

// Per point in the tree's leaf order: consecutive queries touch the same tree nodes and points,
// and the previous point's k neighbours, being k points near this one, bound the search.
std::vector<Eigen::Matrix3f> plane_covariances(const GicpIndex& index, int k, double epsilon, int threads) {
  const std::size_t n = index.indexed(), kk = static_cast<std::size_t>(std::max(k, 1));
  std::vector<Eigen::Matrix3f> covs(index.size(), Eigen::Matrix3f::Identity());
  if (n == 0) return covs;
  const std::vector<std::uint32_t>& order = index.leaf_order();
  parallel_chunks(n, threads, [&](std::size_t begin, std::size_t end, std::size_t) {
    std::vector<std::uint32_t> idx(kk);
    std::vector<float> d2(kk);
    std::size_t m = 0;
    for (std::size_t j = begin; j < end; ++j) {
      const std::uint32_t i = order[j];
      const Eigen::Vector3f& q = index.point(i);
      float bound = std::numeric_limits<float>::infinity();
      if (m == kk) {  // a margin above the farthest so rounding cannot exclude a k-th nearest there
        bound = 0.0f;
        for (std::size_t t = 0; t < m; ++t) bound = std::max(bound, (index.point(idx[t]) - q).squaredNorm());
        bound = bound * (1.0f + 1e-4f) + 1e-12f;
      }
      m = index.knn(q, kk, idx.data(), d2.data(), bound);
      if (m < kk && bound < std::numeric_limits<float>::infinity()) m = index.knn(q, kk, idx.data(), d2.data());
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

GicpResult gicp_align(const GicpCloud& source, const GicpCloud& target, const SE3& guess, const GicpParams& p,
                      std::vector<std::uint32_t>* matches) {
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
  std::vector<MatchState> state(source.size());
  for (res.iterations = 1; res.iterations <= p.max_iterations; ++res.iterations) {
    const Linearization L = linearize(source, target, T, p, state);
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
  if (matches) {  // at the returned pose, which the last update moved by less than the convergence step
    matches->assign(source.size(), kNoMatch);
    const MatchBounds b(p);
    parallel_chunks(source.size(), std::max(1, p.threads), [&](std::size_t begin, std::size_t end, std::size_t) {
      for (std::size_t i = begin; i < end; ++i) {
        std::uint32_t j = 0;
        float d2 = 0.0f;
        if (find_match(target.index, (T * source.points[i].cast<double>()).cast<float>(), b.max_d, b.max_d2, b.cap,
                       state[i], j, d2))
          (*matches)[i] = j;
      }
    });
  }
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
