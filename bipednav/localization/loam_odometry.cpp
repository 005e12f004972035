#include "bipednav/localization/loam_odometry.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::localization {

void OdometryParams::validate() const {
  require(scan_period_s > 0.0, "scan_period_s", "> 0");
  association.validate();
  require(correspondence_rounds >= 1, "correspondence_rounds", ">= 1");
  require(relaxation > 0.0 && relaxation <= 1.0, "relaxation", "in (0, 1]");
  require(round_converged_translation_m > 0.0, "round_converged_translation_m", "> 0");
  require(round_converged_rotation_rad > 0.0, "round_converged_rotation_rad", "> 0");
  require(min_constraints >= 6, "min_constraints", ">= 6");
  lm.validate();
}

double time_fraction(const PointCloud& c, std::size_t i, double scan_period_s) {
  if (!c.has_time()) return 1.0;
  return std::clamp(static_cast<double>(c.time_offsets_s[i]) / scan_period_s, 0.0, 1.0);
}

void deskew_points_to_end(const PointCloud& cloud, const SE3& T_start_end, double scan_period_s,
                          std::vector<Eigen::Vector3f>& out) {
  const Vector6d x = se3_to_motion(T_start_end);
  const SE3 T_end_start = T_start_end.inverse();
  out.resize(cloud.size());
  // One transform per distinct time: a VLP-16 sweep comes column by column, 16 points at a time.
  double last_s = -1.0;
  SE3 A = SE3::Identity();
  double next_s = out.empty() ? 0.0 : time_fraction(cloud, 0, scan_period_s);  // of point i + 1, once
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double s = next_s;
    if (i + 1 < out.size()) next_s = time_fraction(cloud, i + 1, scan_period_s);
    const Eigen::Vector3d p = cloud.points[i].cast<double>();
    if (s != last_s) {
      const bool shared = i + 1 < out.size() && next_s == s;
      if (!shared) {  // a time of its own (feature clouds): move the point, no transform to compose
        out[i] = (T_end_start * apply_motion(x, s, p)).cast<float>();
        continue;
      }
      A = T_end_start * motion_to_se3(x, s);
      last_s = s;
    }
    out[i] = (A * p).cast<float>();
  }
}

PointCloud deskew_to_end(const PointCloud& cloud, const SE3& T_start_end, double scan_period_s) {
  PointCloud out = cloud.empty_copy();
  out.time_offsets_s = cloud.time_offsets_s;
  out.rings = cloud.rings;
  out.intensities = cloud.intensities;
  deskew_points_to_end(cloud, T_start_end, scan_period_s, out.points);
  return out;
}

LoamOdometry::LoamOdometry(OdometryParams p) : p_(std::move(p)) { p_.validate(); }

void LoamOdometry::reset() {
  for (PointCloud* c : {&raw_edges_, &raw_planars_, &ref_edges_, &ref_planars_}) c->clear();
  raw_motion_ = SE3::Identity();
  ref_stale_ = false;
}

void LoamOdometry::set_reference(const LoamFeatures& f, const SE3& T_start_end) {
  raw_edges_ = f.map_edges;
  raw_planars_ = f.map_planars;
  raw_motion_ = T_start_end;
  ref_stale_ = true;
}

void LoamOdometry::deskew_reference() const {
  if (!ref_stale_) return;
  ref_edges_ = deskew_to_end(raw_edges_, raw_motion_, p_.scan_period_s);
  ref_planars_ = deskew_to_end(raw_planars_, raw_motion_, p_.scan_period_s);
  ref_stale_ = false;
}

const PointCloud& LoamOdometry::reference_edges() const {
  deskew_reference();
  return ref_edges_;
}

const PointCloud& LoamOdometry::reference_planars() const {
  deskew_reference();
  return ref_planars_;
}

void LoamOdometry::MovingReference::update(const PointCloud& raw, const SE3& T, double scan_period_s) {
  deskew_points_to_end(raw, T, scan_period_s, positions);
  bool rebuild = tree.size() != positions.size();
  for (std::size_t i = 0; i < positions.size() && !rebuild; ++i)
    rebuild = (positions[i] - tree.point(i)).squaredNorm() > kRebuildM * kRebuildM;
  if (rebuild) tree.build(positions);
}

std::vector<Constraint> LoamOdometry::associate(const LoamFeatures& f, const Vector6d& x,
                                                const Vector6d& reference_offset) {
  const SE3 T = motion_to_se3(x + reference_offset);
  work_.edges.update(raw_edges_, T, p_.scan_period_s);
  work_.planars.update(raw_planars_, T, p_.scan_period_s);
  const MovedPoints edge_points = work_.edges.points(), planar_points = work_.planars.points();
  std::vector<Constraint> cs;
  cs.reserve(f.edges.size() + f.planars.size());
  Constraint c;
  std::vector<NeighbourHint>&edge_hints = work_.edge_hints, &planar_hints = work_.planar_hints;
  edge_hints.resize(f.edges.size());
  planar_hints.resize(f.planars.size());
  for (std::size_t i = 0; i < f.edges.size(); ++i) {
    const Eigen::Vector3d p = f.edges.points[i].cast<double>();
    const double s = time_fraction(f.edges, i, p_.scan_period_s);
    if (edge_correspondence(edge_points, p, s, apply_motion(x, s, p), p_.association, c, nullptr, &edge_hints[i]))
      cs.push_back(c);
  }
  for (std::size_t i = 0; i < f.planars.size(); ++i) {
    const Eigen::Vector3d p = f.planars.points[i].cast<double>();
    const double s = time_fraction(f.planars, i, p_.scan_period_s);
    if (planar_correspondence(planar_points, p, s, apply_motion(x, s, p), p_.association, c, nullptr, &planar_hints[i]))
      cs.push_back(c);
  }
  return cs;
}

OdometryResult LoamOdometry::estimate(const LoamFeatures& f, const SE3& guess, const Vector6d& reference_offset) {
  OdometryResult res;
  res.T_start_end = guess;
  if (!has_reference()) return res;
  const Vector6d offset = reference_offset.allFinite() ? reference_offset : Vector6d::Zero();
  Vector6d x = se3_to_motion(guess);
  for (int round = 0; round < p_.correspondence_rounds; ++round) {
    const std::vector<Constraint> cs = associate(f, x, offset);
    ++res.rounds;
    res.constraints = cs.size();
    if (cs.size() < p_.min_constraints) {
      res.matched = false;
      res.T_start_end = guess;
      return res;
    }
    const LmSolution sol = solve_lm(cs, x, p_.lm);
    const Vector6d change = p_.relaxation * (sol.x - x);
    x += change;
    res.degenerate_dims = sol.degenerate_dims;
    res.inliers = sol.inliers;
    res.rms_m = sol.rms_m;
    res.iterations += sol.iterations;
    if (change.head<3>().norm() < p_.round_converged_translation_m &&
        change.tail<3>().norm() < p_.round_converged_rotation_rad)
      break;
  }
  res.matched = x.allFinite() && res.inliers >= p_.min_constraints;
  res.T_start_end = res.matched ? motion_to_se3(x) : guess;
  return res;
}

}  // namespace bipednav::localization
