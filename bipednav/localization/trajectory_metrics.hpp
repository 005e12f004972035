#pragma once

#include <cstddef>
#include <vector>

#include "bipednav/common/se3.hpp"

namespace bipednav::localization {

// Accuracy of an estimated trajectory against reference poses sampled at the same instants: the
// absolute and relative pose errors as evo defines them (Grupp, 2017; Sturm et al., IROS 2012) and
// the KITTI odometry benchmark's relative errors (Geiger, Lenz and Urtasun, CVPR 2012, devkit
// evaluate_odometry.cpp). Every function throws Error unless both trajectories are non-empty and
// of equal length.

// Summary of a set of errors (all zero when the set is empty).
struct ErrorStats {
  double rmse = 0.0, mean = 0.0, median = 0.0, max = 0.0;
  std::size_t count = 0;
};
ErrorStats error_stats(std::vector<double> errors);

// The rigid transform T (no scale) minimising sum_i |truth_i - T estimate_i|^2 (Umeyama, PAMI
// 1991, eq. 39-41 with c = 1). Fewer than 3 points, or all of them collinear, leave the rotation
// about the line undetermined: the SVD's choice is kept.
SE3 align_rigid(const std::vector<Eigen::Vector3d>& truth, const std::vector<Eigen::Vector3d>& estimate);

// ATE: the translation errors |t(truth_i) - t(T estimate_i)| with T = align_rigid of the positions.
struct AbsoluteError {
  SE3 T_truth_estimate = SE3::Identity();
  ErrorStats translation_m;
};
AbsoluteError absolute_trajectory_error(const std::vector<SE3>& truth, const std::vector<SE3>& estimate);

// RPE over pairs (i, j): E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j), Q the truth, P the estimate; the
// translation |t(E)| and the rotation angle of E. No alignment is needed (the pairs are relative).
struct RelativeError {
  ErrorStats translation_m, rotation_deg;
};
// Pairs (i, i + delta_frames).
RelativeError relative_pose_error(const std::vector<SE3>& truth, const std::vector<SE3>& estimate,
                                  std::size_t delta_frames);
// Pairs (i, j) with j the first frame whose path length from i (along the truth) is >= delta_m.
RelativeError relative_pose_error_at_distance(const std::vector<SE3>& truth, const std::vector<SE3>& estimate,
                                              double delta_m);

// Cumulative 3D path length of the truth at each frame (the devkit's trajectoryDistances).
std::vector<double> path_distances(const std::vector<SE3>& truth);

// KITTI's segment errors: from every step_frames-th first frame, for each length L, the segment
// ends at the first frame whose distance exceeds the first's by more than L; its error is
// E = (P_first^-1 P_last)^-1 (Q_first^-1 Q_last), translation |t(E)| / L and rotation angle(E) / L
// with angle = acos(clamp((trace(R) - 1) / 2)). The benchmark averages them over all segments.
struct KittiErrorParams {
  std::vector<double> lengths_m = {100, 200, 300, 400, 500, 600, 700, 800};
  std::size_t step_frames = 10;
  void validate() const;
};
struct KittiError {
  double translation_percent = 0.0;    // mean of |t(E)| / L, times 100
  double rotation_deg_per_m = 0.0;     // mean of angle(E) / L
  std::size_t segments = 0;            // 0: no length fits in the trajectory (the means are 0)
  std::vector<double> lengths_used_m;  // the lengths that produced at least one segment
};
KittiError kitti_relative_error(const std::vector<SE3>& truth, const std::vector<SE3>& estimate,
                                const KittiErrorParams& p = {});
// Every whole metre 1, 2, ... shorter than the trajectory's path length: the segment lengths of a
// sequence too short for the benchmark's 100-800 m.
std::vector<double> whole_metre_lengths(const std::vector<SE3>& truth);

// |t(estimate.back()) - t(truth.back())| (the trajectories share their frame; no alignment).
double end_point_error_m(const std::vector<SE3>& truth, const std::vector<SE3>& estimate);

}  // namespace bipednav::localization
