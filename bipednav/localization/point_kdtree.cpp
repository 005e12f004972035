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

PointKdTree::PointKdTree(std::vector<Eigen::Vector3f> points) { build(std::move(points)); }

void PointKdTree::build(std::vector<Eigen::Vector3f> points) {
  ++generation_.value;
  points_ = std::move(points);
  ids_.clear();
  x_.clear();
  y_.clear();
  z_.clear();
  nodes_.clear();
  std::vector<Slot> slots;
  slots.reserve(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i)
    if (points_[i].allFinite()) slots.push_back({points_[i], static_cast<std::uint32_t>(i)});
  if (slots.empty()) return;
  nodes_.reserve(4 * slots.size() / kLeafSize + 2);
  build_node(slots, 0, static_cast<std::uint32_t>(slots.size()));
  ids_.resize(slots.size());
  x_.resize(slots.size());
  y_.resize(slots.size());
  z_.resize(slots.size());
  for (std::size_t s = 0; s < slots.size(); ++s) {
    ids_[s] = slots[s].id;
    x_[s] = slots[s].p.x();
    y_[s] = slots[s].p.y();
    z_[s] = slots[s].p.z();
  }
}

// Median split on the axis of largest extent: a balanced tree whatever the point density. The
// points are moved with their indices (no indirection while partitioning); nth_element sees the
// same comparisons as on the indices alone, so it leaves the same order.
std::uint32_t PointKdTree::build_node(std::vector<Slot>& slots, std::uint32_t begin, std::uint32_t end) {
  const auto index = static_cast<std::uint32_t>(nodes_.size());
  nodes_.emplace_back();
  if (end - begin <= kLeafSize) {
    nodes_[index].begin = begin;
    nodes_[index].count = static_cast<std::uint16_t>(end - begin);
    nodes_[index].dim = kLeaf;
    return index;
  }
  Eigen::Vector3f lo = slots[begin].p, hi = lo;
  for (std::uint32_t s = begin + 1; s < end; ++s) {
    lo = lo.cwiseMin(slots[s].p);
    hi = hi.cwiseMax(slots[s].p);
  }
  Eigen::Index dim = 0;
  (hi - lo).maxCoeff(&dim);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(slots.begin() + begin, slots.begin() + mid, slots.begin() + end,
                   [dim](const Slot& a, const Slot& b) { return a.p[dim] < b.p[dim]; });
  float left_max = slots[begin].p[dim];
  for (std::uint32_t s = begin + 1; s < mid; ++s) left_max = std::max(left_max, slots[s].p[dim]);
  nodes_[index].lo = left_max;
  nodes_[index].hi = slots[mid].p[dim];
  nodes_[index].dim = static_cast<std::uint8_t>(dim);
  build_node(slots, begin, mid);
  const std::uint32_t right = build_node(slots, mid, end);
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
