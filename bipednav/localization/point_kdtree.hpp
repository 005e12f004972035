#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

namespace bipednav::localization {

// An exact 3D kd-tree specialised for GICP's many small queries: median splits on the widest
// axis, and the points copied into leaf order as separate x / y / z arrays, so a leaf is one
// contiguous, vectorisable scan and neighbouring leaves are neighbours in memory.
// Non-finite points are not indexed (never returned). Queries allocate nothing.
class PointKdTree {
 public:
  PointKdTree() = default;
  explicit PointKdTree(std::vector<Eigen::Vector3f> points);

  // Indexes `points` instead of the tree's points (the buffers' capacity is kept).
  void build(std::vector<Eigen::Vector3f> points);

  bool empty() const { return ids_.empty(); }
  // Counts the changes of this tree object: build() and assigning to it each add one, so the
  // tree's address and generation name its points for as long as it lives (a cache of results
  // against a tree compares both). 0 for a default-constructed tree.
  std::uint64_t generation() const { return generation_.value; }
  std::size_t indexed() const { return ids_.size(); }
  std::size_t size() const { return points_.size(); }
  const Eigen::Vector3f& point(std::size_t i) const { return points_[i]; }

  // Indices of the indexed points in leaf order (neighbouring entries are spatially close).
  const std::vector<std::uint32_t>& leaf_order() const { return ids_; }

  // The nearest point of q closer than sqrt(bound_sq): writes its index and squared distance and
  // returns true, or returns false when there is none. A tight bound makes the search cheap.
  bool nearest(const Eigen::Vector3f& q, float bound_sq, std::uint32_t& index, float& sq_dist) const;

  // The k nearest points of q closer than sqrt(bound_sq), nearest first: writes indices and
  // squared distances, returns how many were found (fewer than k when the bound or the points
  // run out).
  std::size_t knn(const Eigen::Vector3f& q, std::size_t k, std::uint32_t* indices, float* sq_dists,
                  float bound_sq = std::numeric_limits<float>::infinity()) const;

 private:
  struct Node {
    float lo = 0.0f, hi = 0.0f;  // inner: the left child's maximum and the right child's minimum on `dim`
    std::uint32_t begin = 0;     // leaf: first slot; inner: index of the right child (the left is next)
    std::uint16_t count = 0;     // leaf: number of slots
    std::uint8_t dim = 0;        // 0..2 inner, kLeaf for a leaf
  };
  static constexpr std::uint8_t kLeaf = 3;
  struct Knn;
  struct Nearest;

  struct Slot {
    Eigen::Vector3f p;
    std::uint32_t id;
  };
  std::uint32_t build_node(std::vector<Slot>& slots, std::uint32_t begin, std::uint32_t end);

  // A counter that a copy or move assignment of the tree advances instead of copying.
  struct Generation {
    std::uint64_t value = 0;
    Generation() = default;
    Generation(const Generation&) = default;
    Generation& operator=(const Generation&) {
      ++value;
      return *this;
    }
  };
  template <class Result>
  void search(std::uint32_t node, const float* q, float* offset, float cell_sq, Result& r) const;

  std::vector<Eigen::Vector3f> points_;  // as given
  std::vector<std::uint32_t> ids_;       // slot -> index into points_
  std::vector<float> x_, y_, z_;         // per slot, leaf order
  std::vector<Node> nodes_;              // preorder, root first
  Generation generation_;
};

}  // namespace bipednav::localization
