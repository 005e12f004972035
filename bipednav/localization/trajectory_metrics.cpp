#include "bipednav/localization/trajectory_metrics.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::localization {

namespace {

void check_pair(const std::vector<SE3>& truth, const std::vector<SE3>& estimate, const char* what) {
  if (truth.empty() || truth.size() != estimate.size())
    throw Error(std::string(what) + ": expected two non-empty trajectories of equal length (got " +
                std::to_string(truth.size()) + " and " + std::to_string(estimate.size()) + " poses)");
}

// Angle of a rotation as the devkit's rotationError computes it.
double rotation_angle_rad(const Eigen::Matrix3d& R) {
  return std::acos(std::clamp(0.5 * (R.trace() - 1.0), -1.0, 1.0));
}

SE3 relative_error(const std::vector<SE3>& truth, const std::vector<SE3>& estimate, std::size_t i, std::size_t j) {
  return (truth[i].inverse() * truth[j]).inverse() * (estimate[i].inverse() * estimate[j]);
}

RelativeError relative_errors_of(const std::vector<SE3>& truth, const std::vector<SE3>& estimate,
                                 const std::vector<std::pair<std::size_t, std::size_t>>& pairs) {
  std::vector<double> t, r;
  for (const auto& [i, j] : pairs) {
    const SE3 E = relative_error(truth, estimate, i, j);
    t.push_back(E.translation().norm());
    r.push_back(rad2deg(rotation_angle_rad(E.linear())));
  }
  return {error_stats(std::move(t)), error_stats(std::move(r))};
}

}  // namespace

ErrorStats error_stats(std::vector<double> errors) {
  ErrorStats s;
  s.count = errors.size();
  if (errors.empty()) return s;
  double sq = 0.0;
  for (const double e : errors) sq += e * e;
  s.rmse = std::sqrt(sq / static_cast<double>(errors.size()));
  s.mean = std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
  std::sort(errors.begin(), errors.end());
  const std::size_t n = errors.size();
  s.median = n % 2 == 1 ? errors[n / 2] : 0.5 * (errors[n / 2 - 1] + errors[n / 2]);
  s.max = errors.back();
  return s;
}

SE3 align_rigid(const std::vector<Eigen::Vector3d>& truth, const std::vector<Eigen::Vector3d>& estimate) {
  if (truth.empty() || truth.size() != estimate.size())
    throw Error("align_rigid: expected two non-empty point sets of equal size");
  const double n = static_cast<double>(truth.size());
  Eigen::Vector3d mu_t = Eigen::Vector3d::Zero(), mu_e = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < truth.size(); ++i) {
    mu_t += truth[i];
    mu_e += estimate[i];
  }
  mu_t /= n;
  mu_e /= n;
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();  // eq. 38: the cross-covariance
  for (std::size_t i = 0; i < truth.size(); ++i) sigma += (truth[i] - mu_t) * (estimate[i] - mu_e).transpose();
  sigma /= n;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();  // eq. 39: a reflection is turned into a rotation
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) S(2, 2) = -1.0;
  SE3 T = SE3::Identity();
  T.linear() = svd.matrixU() * S * svd.matrixV().transpose();  // eq. 40
  T.translation() = mu_t - T.linear() * mu_e;                  // eq. 41
  return T;
}

AbsoluteError absolute_trajectory_error(const std::vector<SE3>& truth, const std::vector<SE3>& estimate) {
  check_pair(truth, estimate, "absolute_trajectory_error");
  std::vector<Eigen::Vector3d> pt, pe;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    pt.push_back(truth[i].translation());
    pe.push_back(estimate[i].translation());
  }
  AbsoluteError a;
  a.T_truth_estimate = align_rigid(pt, pe);
  std::vector<double> e;
  for (std::size_t i = 0; i < pt.size(); ++i) e.push_back((pt[i] - a.T_truth_estimate * pe[i]).norm());
  a.translation_m = error_stats(std::move(e));
  return a;
}

RelativeError relative_pose_error(const std::vector<SE3>& truth, const std::vector<SE3>& estimate,
                                  std::size_t delta_frames) {
  check_pair(truth, estimate, "relative_pose_error");
  if (delta_frames < 1) throw Error("relative_pose_error: delta_frames must be >= 1");
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i + delta_frames < truth.size(); ++i) pairs.emplace_back(i, i + delta_frames);
  return relative_errors_of(truth, estimate, pairs);
}

std::vector<double> path_distances(const std::vector<SE3>& truth) {
  std::vector<double> d(truth.size(), 0.0);
  for (std::size_t i = 1; i < truth.size(); ++i)
    d[i] = d[i - 1] + (truth[i].translation() - truth[i - 1].translation()).norm();
  return d;
}

RelativeError relative_pose_error_at_distance(const std::vector<SE3>& truth, const std::vector<SE3>& estimate,
                                              double delta_m) {
  check_pair(truth, estimate, "relative_pose_error_at_distance");
  if (!(delta_m > 0.0 && std::isfinite(delta_m))) throw Error("relative_pose_error_at_distance: delta_m must be > 0");
  const std::vector<double> d = path_distances(truth);
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  std::size_t j = 0;
  for (std::size_t i = 0; i < d.size(); ++i) {
    j = std::max(j, i);
    while (j < d.size() && d[j] - d[i] < delta_m) ++j;
    if (j == d.size()) break;
    pairs.emplace_back(i, j);
  }
  return relative_errors_of(truth, estimate, pairs);
}

void KittiErrorParams::validate() const {
  require(!lengths_m.empty(), "lengths_m", "at least one segment length");
  for (const double l : lengths_m) require(l > 0.0 && std::isfinite(l), "lengths_m", "lengths > 0 m");
  require(step_frames >= 1, "step_frames", ">= 1");
}

KittiError kitti_relative_error(const std::vector<SE3>& truth, const std::vector<SE3>& estimate,
                                const KittiErrorParams& p) {
  check_pair(truth, estimate, "kitti_relative_error");
  p.validate();
  const std::vector<double> dist = path_distances(truth);
  KittiError k;
  double t_sum = 0.0, r_sum = 0.0;
  std::vector<bool> used(p.lengths_m.size(), false);
  for (std::size_t first = 0; first < truth.size(); first += p.step_frames) {
    for (std::size_t l = 0; l < p.lengths_m.size(); ++l) {
      const double len = p.lengths_m[l];
      // lastFrameFromSegmentLength: the first frame strictly farther than len.
      std::size_t last = first;
      while (last < dist.size() && !(dist[last] > dist[first] + len)) ++last;
      if (last == dist.size()) continue;
      // The devkit's pose_error = inv(delta_result) * delta_gt, the inverse of relative_error's E:
      // the same translation norm and angle.
      const SE3 E = (estimate[first].inverse() * estimate[last]).inverse() * (truth[first].inverse() * truth[last]);
      t_sum += E.translation().norm() / len;
      r_sum += rotation_angle_rad(E.linear()) / len;
      ++k.segments;
      used[l] = true;
    }
  }
  for (std::size_t l = 0; l < used.size(); ++l)
    if (used[l]) k.lengths_used_m.push_back(p.lengths_m[l]);
  if (k.segments > 0) {
    k.translation_percent = 100.0 * t_sum / static_cast<double>(k.segments);
    k.rotation_deg_per_m = rad2deg(r_sum / static_cast<double>(k.segments));
  }
  return k;
}

std::vector<double> whole_metre_lengths(const std::vector<SE3>& truth) {
  const std::vector<double> d = path_distances(truth);
  std::vector<double> lengths;
  for (double l = 1.0; !d.empty() && l < d.back(); l += 1.0) lengths.push_back(l);
  return lengths;
}

double end_point_error_m(const std::vector<SE3>& truth, const std::vector<SE3>& estimate) {
  check_pair(truth, estimate, "end_point_error_m");
  return (estimate.back().translation() - truth.back().translation()).norm();
}

}  // namespace bipednav::localization
