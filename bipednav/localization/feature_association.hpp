#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "bipednav/localization/point_kdtree.hpp"
#include "bipednav/localization/registration_lm.hpp"

namespace bipednav::localization {

// Edge-line and planar-patch correspondences of a feature point (eq. 4.6, 4.7): the nearest
// reference features are fitted with a line or a plane, which is accepted only when the
// neighbours really are collinear / coplanar.
struct AssociationParams {
  int neighbours = 5;                  // reference points fitted per feature
  double max_correspondence_m = 1.0;   // all of them must lie this close to the feature
  double max_plane_deviation_m = 0.1;  // of the fitted points from their plane
  double min_line_ratio = 3.0;         // largest / second eigenvalue of an edge's neighbours
  double edge_weight = 0.3;            // edge rows carry the column quantisation of the corner (~ range * azimuth step)
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("neighbours", neighbours);
    v("max_correspondence_m", max_correspondence_m);
    v("max_plane_deviation_m", max_plane_deviation_m);
    v("min_line_ratio", min_line_ratio);
    v("edge_weight", edge_weight);
  }
};

// Where each reference point was seen from (indexed like the tree's points) and where the
// sensor is now, both in the reference frame. The two faces of a thin wall (or the two corners of
// its end) lie closer together than the correspondence distance; a feature on the face seen now
// must not be matched to the other face, seen earlier from the other side, or the estimate is
// pulled through the wall by its thickness.
struct ViewCheck {
  const std::vector<Eigen::Vector3f>* viewpoints = nullptr;
  Eigen::Vector3d sensor = Eigen::Vector3d::Zero();
};

// `q` is the feature point moved into the reference frame with the current estimate; the
// constraint keeps `point` and `s` (the motion is applied to them by the solver). With `view`,
// a patch is rejected unless all its points were seen from the side of its plane the sensor is
// on now (an edge: from the same half-space).
// Points indexed by a kd-tree built on earlier positions of the same points (indexed alike):
// neighbours are searched in the tree, then fitted at `positions`. For points that moved a little
// since (the reference sweep re-de-skewed with a refined motion): rebuilding the tree every
// correspondence round would cost more than the association itself.
struct MovedPoints {
  const PointKdTree* tree = nullptr;
  const std::vector<Eigen::Vector3f>* positions = nullptr;
  bool empty() const { return tree == nullptr || positions == nullptr || tree->empty(); }
  const Eigen::Vector3f& point(std::size_t i) const { return (*positions)[i]; }
};

// The reference points a feature was matched with in an earlier round (as indices of the tree's
// points). Any k distinct indexed points bound the distance of the k-th nearest from above, so
// their distances let the kd-tree search prune from its start; the neighbours found are the same
// with or without a hint (see PointKdTree::knn: the k first by distance, then by visiting order,
// among the points closer than the bound). A match stores the neighbours it searched, and against
// a PointKdTree (whose points do not move) their fit, reused while the same tree (address and
// generation) gives the same neighbours. Hints are kept by the owner of the trees they are used
// with (a hint that outlived its tree could take another tree at the same address for it).
struct NeighbourHint {
  std::array<std::uint32_t, 16> idx{};
  std::uint8_t n = 0;
  const PointKdTree* fit_tree = nullptr;  // the tree the fit below is of (nullptr: none) ...
  std::uint64_t fit_generation = 0;       // ... and its generation() then
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d eigenvalues = Eigen::Vector3d::Zero();
  Eigen::Matrix3d eigenvectors = Eigen::Matrix3d::Identity();
};

// PointKdTree bounds its search by the correspondence distance, so a feature without a match costs
// little; MovedPoints searches a tree whose points were moved (see above).
bool edge_correspondence(const PointKdTree& edges, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                         const AssociationParams& p, Constraint& out, const ViewCheck* view = nullptr,
                         NeighbourHint* hint = nullptr);
bool planar_correspondence(const PointKdTree& planars, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                           const AssociationParams& p, Constraint& out, const ViewCheck* view = nullptr,
                           NeighbourHint* hint = nullptr);
bool edge_correspondence(const MovedPoints& edges, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                         const AssociationParams& p, Constraint& out, const ViewCheck* view = nullptr,
                         NeighbourHint* hint = nullptr);
bool planar_correspondence(const MovedPoints& planars, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                           const AssociationParams& p, Constraint& out, const ViewCheck* view = nullptr,
                           NeighbourHint* hint = nullptr);

}  // namespace bipednav::localization
