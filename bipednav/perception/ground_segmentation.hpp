#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/perception/plane.hpp"

namespace bipednav::perception {

struct RansacParams {
  double distance_threshold_m = 0.03;  // D_threshold of eq. 4.3
  double success_probability = 0.99;   // rho of eq. 4.4, usually in [0.90, 0.99]
  int max_iterations = 1000;           // upper bound on N of eq. 4.4
  bool use_normal_prior = false;       // accept only planes within max_normal_angle_rad of prior_normal
  Eigen::Vector3d prior_normal{0.0, 0.0, 1.0};
  double max_normal_angle_rad = 0.2618;  // 15 deg
  bool refit = true;                     // least-squares refit on the inliers of the best model
  bool inlier_std = true;                // fill PlaneFit::inlier_std_m (one more pass over the points)
  // 0: every finite point. Else the models are sampled, scored and refitted on at most about this
  // many of the finite points (every k-th input point, k = ceil(size / max_points)); PlaneFit's
  // inliers and inlier_std_m are still counted on all points. A fused frame of the TurtleBot3
  // (two depth clouds and a VLP-16 sweep) has 20k-40k points; the ground's plane needs far fewer.
  // The TurtleBot3 uses 4000 (config/turtlebot3.params.yaml) for less perception CPU; the refit plane
  // can move slightly (docs/closed-loop-log.md, 'Parameter evidence').
  std::size_t max_points = 0;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp). prior_normal is left out: the pipeline sets it from
  // PerceptionParams::prior_ground.
  template <class V>
  void visit_fields(V& v) {
    v("distance_threshold_m", distance_threshold_m);
    v("success_probability", success_probability);
    v("max_iterations", max_iterations);
    v("use_normal_prior", use_normal_prior);
    v("max_normal_angle_rad", max_normal_angle_rad);
    v("refit", refit);
    v("inlier_std", inlier_std);
    v("max_points", max_points);
  }
};

struct PlaneFit {
  bool found = false;
  Plane plane = ground_plane_z0();  // [a, b, c, d], unit normal, c >= 0
  std::size_t inliers = 0;          // points with D_i < D_threshold under `plane` (eq. 4.3)
  double inlier_std_m = 0.0;        // standard deviation of the inliers' distances D_i
  int iterations = 0;               // models scored
};

// The finite points of a cloud as separate coordinate arrays, so that scoring a model vectorises.
struct SoaPoints {
  std::vector<float> x, y, z;
  std::vector<std::size_t> index;  // into the input
  std::size_t size() const { return x.size(); }
  Eigen::Vector3d at(std::size_t i) const { return {x[i], y[i], z[i]}; }
};

// fit_plane_ransac's buffers, kept between calls by their owner: a pipeline fits a plane every
// frame, and fresh vectors of this size cost an allocation (and page faults) each time. What they
// held does not change the fit.
struct RansacScratch {
  SoaPoints sampled, all;          // the points the models are scored on; all finite points
  std::vector<std::size_t> refit;  // the best model's inliers
};

// RANSAC plane fit (eq. 4.1-4.4). Each iteration samples 3 distinct points, solves the plane,
// counts the points with D_i < D_threshold; the best model has the most inliers, ties broken by
// the smaller standard deviation of the inlier distances. The iteration count is recomputed after
// every new best from the current inlier ratio u: N = round(log(1 - rho) / log(1 - u^3)) (eq. 4.4,
// with (1 - eps) = u), capped by max_iterations. Degenerate (collinear) samples are redrawn and not
// counted. Non-finite points are ignored. `found` is false for fewer than 3 finite points or when
// no sample gives a plane passing the normal prior; `plane` is then z = 0. With max_points the
// models come from a strided subset (see RansacParams::max_points). Without `scratch` the call
// allocates its own buffers.
PlaneFit fit_plane_ransac(const std::vector<Eigen::Vector3f>& points, const RansacParams& params, Rng& rng,
                          RansacScratch* scratch = nullptr);

// Total least squares plane through the given points (centroid + smallest principal axis),
// normalised (unit normal, c >= 0). Needs at least 3 non-collinear points; otherwise returns z = 0.
Plane fit_plane_least_squares(const std::vector<Eigen::Vector3f>& points, const std::vector<std::size_t>& indices);

}  // namespace bipednav::perception
