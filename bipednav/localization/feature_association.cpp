#include "bipednav/localization/feature_association.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>

#include "bipednav/common/error.hpp"

namespace bipednav::localization {

namespace {

constexpr std::size_t kMaxNeighbours = 16;

// Mean and principal axes of the neighbours of q (all within the correspondence distance).
struct LocalFit {
  std::array<std::uint32_t, kMaxNeighbours> idx{};
  std::size_t n = 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d eigenvalues = Eigen::Vector3d::Zero();  // ascending
  Eigen::Matrix3d eigenvectors = Eigen::Matrix3d::Identity();
};

const PointKdTree& search_tree(const PointKdTree& tree) { return tree; }
const PointKdTree& search_tree(const MovedPoints& moved) { return *moved.tree; }

// A tighter search bound from the hint's points (their largest squared distance to q, computed as
// the search computes distances, with a margin for rounding), or `bound` unchanged.
float hinted_bound(const PointKdTree& tree, const Eigen::Vector3f& q, std::size_t k, const NeighbourHint* hint,
                   float bound) {
  if (hint == nullptr || hint->n != k) return bound;
  float worst = 0.0f;
  for (std::size_t i = 0; i < k; ++i) {
    if (hint->idx[i] >= tree.size()) return bound;
    const Eigen::Vector3f& p = tree.point(hint->idx[i]);
    const float dx = p.x() - q.x(), dy = p.y() - q.y(), dz = p.z() - q.z();
    const float d = dx * dx + dy * dy + dz * dz;
    if (!(d <= std::numeric_limits<float>::max())) return bound;  // not indexed (non-finite), or overflow
    worst = std::max(worst, d);
  }
  return std::min(bound, worst * 1.001f + 1e-12f);
}

template <class Tree>
bool fit_neighbours(const Tree& tree, const Eigen::Vector3d& q, const AssociationParams& p, LocalFit& f,
                    NeighbourHint* hint) {
  std::array<float, kMaxNeighbours> d2{};
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(p.neighbours), kMaxNeighbours);
  const auto max_sq = static_cast<float>(p.max_correspondence_m * p.max_correspondence_m);
  const Eigen::Vector3f qf = q.cast<float>();
  if constexpr (std::is_same_v<Tree, MovedPoints>) {
    if (tree.tree->size() != tree.positions->size()) return false;
  }
  const PointKdTree& searched = search_tree(tree);
  // knn() keeps points strictly closer than the bound; points at exactly max_correspondence_m count.
  const float bound =
      hinted_bound(searched, qf, k, hint, std::nextafter(max_sq, std::numeric_limits<float>::infinity()));
  if (searched.knn(qf, k, f.idx.data(), d2.data(), bound) != k) return false;
  f.n = k;
  // A tree's own points do not move (MovedPoints' do): the same neighbours of the same tree as in
  // the previous round give the same fit.
  const PointKdTree* fixed = std::is_same_v<Tree, PointKdTree> ? &searched : nullptr;
  if (hint != nullptr) {
    const bool same = fixed != nullptr && hint->fit_tree == fixed && hint->fit_generation == fixed->generation() &&
                      hint->n == k &&
                      std::equal(f.idx.begin(), f.idx.begin() + static_cast<std::ptrdiff_t>(k), hint->idx.begin());
    std::copy_n(f.idx.begin(), k, hint->idx.begin());
    hint->n = static_cast<std::uint8_t>(k);
    if (same) {
      f.mean = hint->mean;
      f.eigenvalues = hint->eigenvalues;
      f.eigenvectors = hint->eigenvectors;
      return true;
    }
    hint->fit_tree = nullptr;
  }
  for (std::size_t i = 0; i < f.n; ++i) f.mean += tree.point(f.idx[i]).template cast<double>();
  f.mean /= static_cast<double>(f.n);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < f.n; ++i) {
    const Eigen::Vector3d d = tree.point(f.idx[i]).template cast<double>() - f.mean;
    cov.noalias() += d * d.transpose();
  }
  // The closed-form 3x3 solver: the iterative one costs several times more per correspondence.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(cov / static_cast<double>(f.n));
  f.eigenvalues = es.eigenvalues();
  f.eigenvectors = es.eigenvectors();
  if (hint != nullptr && fixed != nullptr) {
    hint->fit_tree = fixed;
    hint->fit_generation = fixed->generation();
    hint->mean = f.mean;
    hint->eigenvalues = f.eigenvalues;
    hint->eigenvectors = f.eigenvectors;
  }
  return true;
}

// Every neighbour seen from the side of `axis` (through the fit's mean) the sensor is on now.
bool seen_from_this_side(const LocalFit& f, const Eigen::Vector3d& axis, const ViewCheck* view) {
  if (view == nullptr || view->viewpoints == nullptr) return true;
  const double now = axis.dot(view->sensor - f.mean);
  for (std::size_t i = 0; i < f.n; ++i) {
    if (f.idx[i] >= view->viewpoints->size()) return false;
    if (now * axis.dot((*view->viewpoints)[f.idx[i]].cast<double>() - f.mean) <= 0.0) return false;
  }
  return true;
}

}  // namespace

void AssociationParams::validate() const {
  require(neighbours >= 3 && neighbours <= static_cast<int>(kMaxNeighbours), "neighbours", "in [3, 16]");
  require(max_correspondence_m > 0.0, "max_correspondence_m", "> 0");
  require(max_plane_deviation_m > 0.0, "max_plane_deviation_m", "> 0");
  require(min_line_ratio > 1.0, "min_line_ratio", "> 1");
  require(edge_weight >= 0.0 && edge_weight <= 1.0, "edge_weight", "in [0, 1]");
}

namespace {

template <class Tree>
bool edge_match(const Tree& edges, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                const AssociationParams& p, Constraint& out, const ViewCheck* view, NeighbourHint* hint) {
  LocalFit f;
  if (edges.empty() || !fit_neighbours(edges, q, p, f, hint)) return false;
  if (f.eigenvalues(2) < p.min_line_ratio * f.eigenvalues(1)) return false;
  const Eigen::Vector3d u = f.eigenvectors.col(2);
  if (view != nullptr) {  // the half-space facing the sensor now, bounded through the line
    const Eigen::Vector3d to_sensor = view->sensor - f.mean;
    const Eigen::Vector3d across = to_sensor - u.dot(to_sensor) * u;
    if (across.norm() < 1e-6 || !seen_from_this_side(f, across.normalized(), view)) return false;
  }
  out = line_constraint(point, s, f.mean - 0.1 * u, f.mean + 0.1 * u);  // two points of the line (eq. 4.6)
  out.weight = p.edge_weight;
  return true;
}

template <class Tree>
bool planar_match(const Tree& planars, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                  const AssociationParams& p, Constraint& out, const ViewCheck* view, NeighbourHint* hint) {
  LocalFit f;
  if (planars.empty() || !fit_neighbours(planars, q, p, f, hint)) return false;
  const Eigen::Vector3d normal = f.eigenvectors.col(0);
  for (std::size_t t = 0; t < f.n; ++t)
    if (std::abs(normal.dot(planars.point(f.idx[t]).template cast<double>() - f.mean)) > p.max_plane_deviation_m)
      return false;
  if (!seen_from_this_side(f, normal, view)) return false;
  out.point = point;  // the patch's plane (eq. 4.7) through its centroid
  out.s = s;
  out.anchor = f.mean;
  out.axis = normal;
  out.is_line = false;
  out.weight = 1.0;
  return true;
}

}  // namespace

bool edge_correspondence(const PointKdTree& edges, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                         const AssociationParams& p, Constraint& out, const ViewCheck* view, NeighbourHint* hint) {
  return edge_match(edges, point, s, q, p, out, view, hint);
}

bool planar_correspondence(const PointKdTree& planars, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                           const AssociationParams& p, Constraint& out, const ViewCheck* view, NeighbourHint* hint) {
  return planar_match(planars, point, s, q, p, out, view, hint);
}

bool edge_correspondence(const MovedPoints& edges, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                         const AssociationParams& p, Constraint& out, const ViewCheck* view, NeighbourHint* hint) {
  return edge_match(edges, point, s, q, p, out, view, hint);
}

bool planar_correspondence(const MovedPoints& planars, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                           const AssociationParams& p, Constraint& out, const ViewCheck* view, NeighbourHint* hint) {
  return planar_match(planars, point, s, q, p, out, view, hint);
}

}  // namespace bipednav::localization
