#pragma once

#include "bipednav/localization/kdtree.hpp"
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
};

// `q` is the feature point moved into the reference frame with the current estimate; the
// constraint keeps `point` and `s` (the motion is applied to them by the solver).
bool edge_correspondence(const KdTree3f& edges, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                         const AssociationParams& p, Constraint& out);
bool planar_correspondence(const KdTree3f& planars, const Eigen::Vector3d& point, double s, const Eigen::Vector3d& q,
                           const AssociationParams& p, Constraint& out);

}  // namespace bipednav::localization
