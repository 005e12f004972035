#include "bipednav/localization/loam.hpp"

#include <cmath>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::localization {

namespace {

bool finite(const SE3& T) { return T.matrix().allFinite(); }

void append_reason(LoamOutput& out, const std::string& r) { out.reason += (out.reason.empty() ? "" : "; ") + r; }

}  // namespace

SE3 project_to_plane(const SE3& T, const SE3& anchor) {
  const double anchor_yaw = matrix_to_rpy(anchor.linear())(2);
  const Eigen::Matrix3d tilt = rpy_to_matrix(0.0, 0.0, -anchor_yaw) * anchor.linear();
  const Eigen::Matrix3d R = T.linear() * tilt.transpose();
  SE3 out = SE3::Identity();
  out.linear() = rpy_to_matrix(0.0, 0.0, std::atan2(R(1, 0), R(0, 0))) * tilt;
  out.translation() = Eigen::Vector3d(T.translation().x(), T.translation().y(), anchor.translation().z());
  return out;
}

void LoamParams::validate() const {
  features.validate();
  odometry.validate();
  mapping.validate();
  require(min_features >= 6, "min_features", ">= 6");
  require(max_prior_change_m >= 0.0 && std::isfinite(max_prior_change_m), "max_prior_change_m", ">= 0 and finite");
  require(max_prior_change_rad >= 0.0 && std::isfinite(max_prior_change_rad), "max_prior_change_rad",
          ">= 0 and finite");
  require(max_prior_error_change_rad >= 0.0 && std::isfinite(max_prior_error_change_rad), "max_prior_error_change_rad",
          ">= 0 and finite");
  require(finite(T_world_lidar_initial), "T_world_lidar_initial", "a finite transform");
}

Loam::Loam(LoamParams p) : p_(std::move(p)), odometry_(p_.odometry), mapping_(p_.mapping) {
  p_.validate();
  reset();
}

void Loam::reset() {
  odometry_.reset();
  mapping_.reset();
  sweeps_ = 0;
  const double per_sweep = p_.mapping.rate_hz * p_.odometry.scan_period_s;
  mapping_every_ = per_sweep <= 0.0 ? 1 : static_cast<std::size_t>(std::max(1.0, std::round(1.0 / per_sweep)));
  last_motion_ = SE3::Identity();
  last_prior_.reset();
  last_prior_error_.reset();
  T_odom_lidar_ = SE3::Identity();
  T_world_odom_ = p_.T_world_lidar_initial;
  last_good_ = p_.T_world_lidar_initial;
  anchor_ = p_.T_world_lidar_initial;
}

SE3 Loam::level(const SE3& T_world_lidar) const {
  return p_.planar_motion ? project_to_plane(T_world_lidar, anchor_) : T_world_lidar;
}

void Loam::set_pose(const SE3& T_world_lidar) {
  if (!finite(T_world_lidar)) throw Error("Loam::set_pose: the pose is not finite");
  mapping_.reset();
  T_world_odom_ = T_world_lidar * T_odom_lidar_.inverse();
  last_good_ = T_world_lidar;
  anchor_ = T_world_lidar;
}

std::optional<Vector6d> Loam::reference_offset(const std::optional<SE3>& prior) const {
  if (!p_.reference_from_prior_change || !prior || !last_prior_ || !last_prior_error_) return std::nullopt;
  Vector6d d = *last_prior_ - se3_to_motion(*prior);
  if (!d.allFinite() || d.head<3>().norm() > p_.max_prior_change_m || d.tail<3>().norm() > p_.max_prior_change_rad)
    return std::nullopt;
  // Only the rotation: a slip's translation error (0.7 x 0.022 m per sweep for the fault runs'
  // slip at 0.22 m/s) is below the closed loop's sweep-to-sweep noise of prior - estimate
  // (p95 ~0.013 m in x and y, turtlebot3 in hexagon_static), so the check below cannot see it.
  d.head<3>().setZero();
  return d;
}

bool Loam::prior_error_steady(const SE3& prior, const SE3& estimate) const {
  if (!last_prior_error_) return false;
  const Vector6d d = *last_prior_error_ - (se3_to_motion(prior) - se3_to_motion(estimate));
  return d.allFinite() && d.tail<3>().norm() <= p_.max_prior_error_change_rad;
}

SE3 Loam::odometry_step(const LoamFeatures& f, const SE3& guess, bool prior_given, const Vector6d& reference_offset,
                        LoamOutput& out) {
  if (!odometry_.has_reference()) {
    if (sweeps_ > 0) {
      out.healthy = false;
      append_reason(out, "no usable previous sweep, motion from " +
                             std::string(prior_given ? "the motion prior" : "constant velocity"));
    }
    return guess;
  }
  const OdometryResult r = odometry_.estimate(f, guess, reference_offset);
  if (!r.matched) {
    out.healthy = false;
    append_reason(out, "odometry: too few correspondences (" + std::to_string(r.constraints) + ")");
    return guess;
  }
  if (r.degenerate_dims > 0) {
    out.degenerate = true;
    append_reason(out, "odometry degenerate in " + std::to_string(r.degenerate_dims) + " direction(s), kept from " +
                           (prior_given ? "the motion prior" : "constant velocity"));
  }
  return r.T_start_end;
}

void Loam::mapping_step(LoamOutput& out, const std::optional<Eigen::Vector3d>& up_in_lidar) {
  Stopwatch sw;
  const MappingResult m = mapping_.process(odometry_.reference_edges(), odometry_.reference_planars(),
                                           T_world_odom_ * T_odom_lidar_, up_in_lidar);
  out.mapped = true;
  if (m.matched && finite(m.T_world_lidar)) {
    T_world_odom_ = level(m.T_world_lidar) * T_odom_lidar_.inverse();
    out.unobserved_xy = m.unobserved_xy;
    if (m.degenerate_dims > 0) {
      out.degenerate = true;
      append_reason(out, "mapping degenerate in " + std::to_string(m.degenerate_dims) + " direction(s)");
    }
  } else if (sweeps_ > 0) {
    append_reason(out, "mapping: too few correspondences (" + std::to_string(m.constraints) + "), odometry kept");
  }
  out.mapping_ms = sw.elapsed_ms();
}

SE3 Loam::constant_velocity_guess() const {
  if (sweeps_ == 0) return SE3::Identity();
  if (!p_.planar_constant_velocity) return last_motion_;
  Vector6d x = se3_to_motion(last_motion_);
  x(2) = x(3) = x(4) = 0.0;
  return motion_to_se3(x);
}

LoamOutput Loam::process(const PointCloud& sweep, const std::optional<SE3>& motion_prior,
                         const std::optional<Eigen::Vector3d>& up_in_lidar) {
  Stopwatch sw;
  LoamOutput out;
  PointCloud dropped;
  const PointCloud& clean = sanitized(sweep, p_.features, dropped);
  const bool prior_given = motion_prior.has_value() && finite(*motion_prior);
  if (motion_prior && !prior_given) append_reason(out, "motion prior is not finite, ignored");
  const SE3 guess = prior_given ? *motion_prior : constant_velocity_guess();
  const LoamFeatures f = extract_features(clean, p_.features, &feature_scratch_);
  out.edge_features = f.edges.size();
  out.planar_features = f.planars.size();
  SE3 motion = guess;
  bool odometry_matched = false;
  const bool usable = f.total_features() >= p_.min_features;
  if (sweep.empty()) {
    out.healthy = false;
    append_reason(out, "empty sweep");
  } else if (clean.empty()) {
    out.healthy = false;
    append_reason(out, "no valid points (all " + std::to_string(sweep.size()) + " non-finite or out of range)");
  } else if (!usable) {
    out.healthy = false;
    append_reason(
        out, "too few features (" + std::to_string(f.total_features()) + " < " + std::to_string(p_.min_features) + ")");
  }
  if (usable) {
    const std::optional<Vector6d> offset = reference_offset(prior_given ? motion_prior : std::nullopt);
    LoamOutput trial = out;
    motion = odometry_step(f, guess, prior_given, offset.value_or(Vector6d::Zero()), trial);
    // The change's error shows only once this sweep is estimated: with an unsteady prior error the
    // change was wrong, and the sweep is estimated again as if there were no change.
    trial.prior_change_used = offset && trial.healthy && prior_error_steady(*motion_prior, motion);
    if (offset && !trial.prior_change_used && !offset->isZero()) {
      motion = odometry_step(f, guess, prior_given, Vector6d::Zero(), out);
    } else {
      out = std::move(trial);
    }
    odometry_matched = sweeps_ > 0 && out.healthy;
    odometry_.set_reference(f, motion);
  } else {
    odometry_.reset();  // the next sweep has nothing to match: it starts over from the prior
  }
  if (sweeps_ > 0) {
    T_odom_lidar_ = T_odom_lidar_ * motion;
    if (p_.planar_motion) T_odom_lidar_ = T_world_odom_.inverse() * level(T_world_odom_ * T_odom_lidar_);
  }
  last_motion_ = motion;
  // The offset pairs two consecutive sweeps: it is kept only while this sweep became the reference.
  last_prior_.reset();
  last_prior_error_.reset();
  if (prior_given && usable) {
    last_prior_ = se3_to_motion(*motion_prior);
    if (odometry_matched) last_prior_error_ = *last_prior_ - se3_to_motion(motion);
  }
  out.T_prev_lidar = motion;
  if (p_.output_deskewed) out.deskewed = deskew_to_end(clean, motion, p_.odometry.scan_period_s);
  out.odometry_ms = sw.elapsed_ms();
  // The first sweep's own motion is unknown (it has nothing to match), so mapping starts with the
  // second sweep rather than putting a distorted sweep into the map.
  if (usable && odometry_matched && (sweeps_ - 1) % mapping_every_ == 0) mapping_step(out, up_in_lidar);
  out.T_world_lidar = T_world_odom_ * T_odom_lidar_;
  if (!finite(out.T_world_lidar)) {  // never hand out NaN: fall back to the last good pose
    out.healthy = false;
    append_reason(out, "non-finite pose, previous pose kept");
    const SE3 keep = last_good_;
    reset();
    set_pose(keep);
    out.T_world_lidar = keep;
  }
  last_good_ = out.T_world_lidar;
  ++sweeps_;
  return out;
}

}  // namespace bipednav::localization
