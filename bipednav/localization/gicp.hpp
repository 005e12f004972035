#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/localization/point_kdtree.hpp"

namespace bipednav::localization {

// Generalized-ICP (Segal, Haehnel and Thrun, RSS 2009), the plane-to-plane variant used by the
// second reference (section III) to correct odometry.
struct GicpParams {
  int covariance_neighbours = 20;     // k nearest points per covariance
  double covariance_epsilon = 1e-3;   // plane regularisation: eigenvalues become (1, 1, epsilon)
  double max_correspondence_m = 1.0;  // farther nearest neighbours are not matched
  int max_iterations = 64;
  double converged_translation_m = 1e-4;  // stop when an update is smaller than both
  double converged_rotation_rad = 1e-4;
  double lm_lambda = 1e-6;  // Levenberg-Marquardt damping relative to diag(H)
  int threads = 1;          // worker threads for covariances and linearisation
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("covariance_neighbours", covariance_neighbours);
    v("covariance_epsilon", covariance_epsilon);
    v("max_correspondence_m", max_correspondence_m);
    v("max_iterations", max_iterations);
    v("converged_translation_m", converged_translation_m);
    v("converged_rotation_rad", converged_rotation_rad);
    v("lm_lambda", lm_lambda);
    v("threads", threads);
  }
};

// Exact nearest-neighbour searches over a fixed set of points, with the bounded query GICP's
// correspondence search needs.
using GicpIndex = PointKdTree;

// A cloud ready for GICP: finite points, their regularised covariances and a search index.
struct GicpCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<Eigen::Matrix3f> covariances;
  GicpIndex index;
  std::size_t size() const { return points.size(); }
};

struct GicpResult {
  SE3 T_target_source = SE3::Identity();  // maps source points into the target frame
  double fitness = 0.0;                   // mean squared distance of matched pairs (m^2), as PCL reports it
  bool converged = false;
  int iterations = 0;
  std::size_t correspondences = 0;
  double time_ms = 0.0;
};

// Covariance of each point of `index` from its k nearest neighbours (the point among them), with the
// eigenvalues replaced by (1, 1, epsilon) so every point is modelled as a small plane (Segal et al.,
// section III-B); indexed like the points, queried in the tree's leaf order.
std::vector<Eigen::Matrix3f> plane_covariances(const GicpIndex& index, int k, double epsilon, int threads);

// Drops non-finite points, builds the tree and the covariances.
GicpCloud prepare_gicp_cloud(const PointCloud& cloud, const GicpParams& p);
// The same cloud moved by T (covariances rotated, tree rebuilt).
GicpCloud transform_gicp_cloud(const GicpCloud& cloud, const SE3& T);

// No target point within max_correspondence_m (gicp_align's `matches`).
inline constexpr std::uint32_t kGicpNoMatch = 0xffffffffu;

// Aligns source to target starting from `guess` (T_target_source): Gauss-Newton with LM damping
// on the Mahalanobis distances d_i^T (C_t + R C_s R^T)^-1 d_i, correspondences re-found every
// iteration. Throws Error when either cloud has fewer than covariance_neighbours points.
// `matches` (optional) receives per source point its nearest target point within
// max_correspondence_m at the returned pose (kGicpNoMatch: none): the iterations' searches carry
// over, so most are proven unchanged without a search.
GicpResult gicp_align(const GicpCloud& source, const GicpCloud& target, const SE3& guess, const GicpParams& p,
                      std::vector<std::uint32_t>* matches = nullptr);
GicpResult gicp_align(const PointCloud& source, const PointCloud& target, const SE3& guess, const GicpParams& p = {});

// Removes the ground before alignment (the dominant plane would otherwise decide it, reference
// section III): drops points less than band_m above the ground plane z = 0 of the base frame.
PointCloud remove_ground(const PointCloud& cloud_sensor, const SE3& T_base_sensor, double band_m = 0.05);

}  // namespace bipednav::localization
