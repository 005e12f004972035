#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <nanoflann.hpp>
#include <vector>

namespace bipednav::localization {

// A 3D kd-tree (nanoflann) that owns a copy of its points, so it can be moved freely.
class KdTree3f {
 public:
  KdTree3f() = default;
  explicit KdTree3f(std::vector<Eigen::Vector3f> points) : impl_(std::make_unique<Impl>(std::move(points))) {}

  bool empty() const { return !impl_ || impl_->adaptor.pts.empty(); }
  std::size_t size() const { return impl_ ? impl_->adaptor.pts.size() : 0; }
  const Eigen::Vector3f& point(std::size_t i) const { return impl_->adaptor.pts[i]; }

  // Point indices in the tree's leaf order (neighbouring entries are spatially close).
  const std::vector<std::uint32_t>& leaf_order() const { return impl_->tree.vAcc; }

  // The nearest point of q closer than sqrt(bound_sq): writes its index and squared distance and
  // returns true, or returns false when there is none. A tight bound makes the search cheap.
  bool nearest(const Eigen::Vector3f& q, float bound_sq, std::uint32_t& index, float& sq_dist) const {
    if (empty()) return false;
    NearestWithin r{bound_sq};
    impl_->tree.findNeighbors(r, q.data(), nanoflann::SearchParams());
    if (!r.found) return false;
    index = r.index;
    sq_dist = r.worst;
    return true;
  }

  // The k nearest points of q: writes indices and squared distances, returns how many were found.
  std::size_t knn(const Eigen::Vector3f& q, std::size_t k, std::uint32_t* indices, float* sq_dists) const {
    if (empty()) return 0;
    return impl_->tree.knnSearch(q.data(), k, indices, sq_dists);
  }

 private:
  // nanoflann result set for nearest(): nanoflann offers a point only when its squared distance is
  // below worstDist(); keeps the one closest point under the shrinking bound.
  struct NearestWithin {
    float worst;
    std::uint32_t index = 0;
    bool found = false;
    bool full() const { return true; }
    float worstDist() const { return worst; }
    bool addPoint(float d2, std::uint32_t i) {
      if (d2 < worst) {  // nanoflann compares a whole leaf with the bound at the leaf's start
        worst = d2;
        index = i;
        found = true;
      }
      return true;
    }
  };
  struct Adaptor {
    std::vector<Eigen::Vector3f> pts;
    std::size_t kdtree_get_point_count() const { return pts.size(); }
    float kdtree_get_pt(std::size_t i, std::size_t d) const { return pts[i][static_cast<Eigen::Index>(d)]; }
    template <class BBox>
    bool kdtree_get_bbox(BBox& /*bb*/) const {
      return false;
    }
  };
  using Tree =
      nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>, Adaptor, 3, std::uint32_t>;
  struct Impl {
    explicit Impl(std::vector<Eigen::Vector3f> points)
        : adaptor{std::move(points)}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10)) {}
    Adaptor adaptor;
    Tree tree;
  };
  std::unique_ptr<Impl> impl_;
};

}  // namespace bipednav::localization
