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

  // The k nearest points of q: writes indices and squared distances, returns how many were found.
  std::size_t knn(const Eigen::Vector3f& q, std::size_t k, std::uint32_t* indices, float* sq_dists) const {
    if (empty()) return 0;
    return impl_->tree.knnSearch(q.data(), k, indices, sq_dists);
  }

 private:
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
