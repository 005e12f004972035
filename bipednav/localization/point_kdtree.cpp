#include "bipednav/localization/point_kdtree.hpp"

#include <algorithm>
#include <limits>

namespace bipednav::localization {

namespace {

constexpr std::uint32_t kLeafSize = 8;  // slots per leaf at most

}  // namespace

// Keeps the k best slots sorted by distance in the caller's buffers.
struct PointKdTree::Knn {
  std::uint32_t* slots;
  float* sq;
  std::size_t k;
  std::size_t n = 0;
  float worst = std::numeric_limits<float>::infinity();
  void add(float d, std::uint32_t slot) {
    std::size_t i = n < k ? n++ : k - 1;
    for (; i > 0 && sq[i - 1] > d; --i) {
      sq[i] = sq[i - 1];
      slots[i] = slots[i - 1];
    }
    sq[i] = d;
    slots[i] = slot;
    if (n == k) worst = sq[k - 1];
  }
};

struct PointKdTree::Nearest {
  float worst;
  std::uint32_t slot = 0;
  bool found = false;
  void add(float d, std::uint32_t s) {
    worst = d;
    slot = s;
    found = true;
  }
};

PointKdTree::PointKdTree(std::vector<Eigen::Vector3f> points) : points_(std::move(points)) {
  ids_.reserve(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (points_[i].allFinite()) ids_.push_back(static_cast<std::uint32_t>(i));
  if (ids_.empty()) return;
  nodes_.reserve(4 * ids_.size() / kLeafSize + 2);
  build(0, static_cast<std::uint32_t>(ids_.size()));
  x_.resize(ids_.size());
  y_.resize(ids_.size());
  z_.resize(ids_.size());
  for (std::size_t s = 0; s < ids_.size(); ++s) {
    const Eigen::Vector3f& p = points_[ids_[s]];
    x_[s] = p.x();
    y_[s] = p.y();
    z_[s] = p.z();
  }
}

// Median split on the axis of largest extent: a balanced tree whatever the point density.
std::uint32_t PointKdTree::build(std::uint32_t begin, std::uint32_t end) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  if (end - begin <= kLeafSize) {
    nodes_[index].begin = begin;
    nodes_[index].count = static_cast<std::uint16_t>(end - begin);
    nodes_[index].dim = kLeaf;
    return index;
  }
  Eigen::Vector3f lo = points_[ids_[begin]], hi = lo;
  for (std::uint32_t s = begin + 1; s < end; ++s) {
    lo = lo.cwiseMin(points_[ids_[s]]);
    hi = hi.cwiseMax(points_[ids_[s]]);
  }
  Eigen::Index dim = 0;
  (hi - lo).maxCoeff(&dim);
  const std::uint32_t mid = begin + (end - begin) / 2;
  const auto coord = [&](std::uint32_t id) { return points_[id][dim]; };
  std::nth_element(ids_.begin() + begin, ids_.begin() + mid, ids_.begin() + end,
                   [&](std::uint32_t a, std::uint32_t b) { return coord(a) < coord(b); });
  float left_max = coord(ids_[begin]);
  for (std::uint32_t s = begin + 1; s < mid; ++s) left_max = std::max(left_max, coord(ids_[s]));
  nodes_[index].lo = left_max;
  nodes_[index].hi = coord(ids_[mid]);
  nodes_[index].dim = static_cast<std::uint8_t>(dim);
  build(begin, mid);
  const std::uint32_t right = build(mid, end);
  nodes_[index].begin = right;
  return index;
}

// Depth first, nearer child first; `offset` holds q's per-axis distance to the current cell and
// cell_sq its squared norm, a lower bound for every point below (Arya and Mount's incremental
// distance), so a subtree is skipped once that bound reaches the result's worst distance.
template <class Result>
void PointKdTree::search(std::uint32_t node, const float* q, float* offset, float cell_sq, Result& r) const {
  const Node& n = nodes_[node];
  if (n.dim == kLeaf) {
    float d[kLeafSize];
    for (std::uint32_t j = 0; j < n.count; ++j) {
      const float dx = x_[n.begin + j] - q[0], dy = y_[n.begin + j] - q[1], dz = z_[n.begin + j] - q[2];
      d[j] = dx * dx + dy * dy + dz * dz;
    }
    for (std::uint32_t j = 0; j < n.count; ++j)
      if (d[j] < r.worst) r.add(d[j], n.begin + j);
    return;
  }
  const float below = q[n.dim] - n.lo, above = q[n.dim] - n.hi;
  std::uint32_t first = node + 1, second = n.begin;
  float cut = above;
  if (below + above >= 0.0f) {
    std::swap(first, second);
    cut = below;
  }
  search(first, q, offset, cell_sq, r);
  const float sq = cell_sq - offset[n.dim] * offset[n.dim] + cut * cut;
  if (sq < r.worst) {
    const float saved = offset[n.dim];
    offset[n.dim] = cut;
    search(second, q, offset, sq, r);
    offset[n.dim] = saved;
  }
}

bool PointKdTree::nearest(const Eigen::Vector3f& q, float bound_sq, std::uint32_t& index, float& sq_dist) const {
  if (empty()) return false;
  Nearest r{bound_sq};
  float offset[3] = {0.0f, 0.0f, 0.0f};
  search(0, q.data(), offset, 0.0f, r);
  if (!r.found) return false;
  index = ids_[r.slot];
  sq_dist = r.worst;
  return true;
}

std::size_t PointKdTree::knn(const Eigen::Vector3f& q, std::size_t k, std::uint32_t* indices, float* sq_dists,
                             float bound_sq) const {
  if (empty() || k == 0) return 0;
  Knn r{indices, sq_dists, k};
  r.worst = bound_sq;
  float offset[3] = {0.0f, 0.0f, 0.0f};
  search(0, q.data(), offset, 0.0f, r);
  for (std::size_t i = 0; i < r.n; ++i) indices[i] = ids_[indices[i]];
  return r.n;
}

}  // namespace bipednav::localization
