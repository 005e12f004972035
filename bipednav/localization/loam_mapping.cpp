#include "bipednav/localization/loam_mapping.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::localization {

void MappingParams::validate() const {
  require(edge_leaf_m > 0.0 && planar_leaf_m > 0.0, "edge_leaf_m/planar_leaf_m", "> 0");
  require(map_radius_m > 0.0, "map_radius_m", "> 0");
  association.validate();
  require(correspondence_rounds >= 1, "correspondence_rounds", ">= 1");
  require(min_constraints >= 6, "min_constraints", ">= 6");
  lm.validate();
}

std::int64_t VoxelPointMap::key(const Eigen::Vector3f& p) const {
  const auto cell = [&](float v) {
    return (static_cast<std::int64_t>(std::floor(v / leaf_m_)) + (1 << 20)) & ((1 << 21) - 1);
  };
  return (cell(p.x()) << 42) | (cell(p.y()) << 21) | cell(p.z());
}

void VoxelPointMap::insert(const Eigen::Vector3f& p) {
  if (occupied_.insert(key(p)).second) points_.push_back(p);
}

void VoxelPointMap::crop(const Eigen::Vector3f& centre, double radius_m) {
  const float r2 = static_cast<float>(radius_m * radius_m);
  std::vector<Eigen::Vector3f> kept;
  kept.reserve(points_.size());
  for (const auto& p : points_)
    if ((p - centre).squaredNorm() <= r2) kept.push_back(p);
  if (kept.size() == points_.size()) return;
  clear();
  for (const auto& p : kept) insert(p);
}

void VoxelPointMap::clear() {
  points_.clear();
  occupied_.clear();
}

LoamMapping::LoamMapping(MappingParams p) : p_(std::move(p)), edge_map_(p_.edge_leaf_m), planar_map_(p_.planar_leaf_m) {
  p_.validate();
}

void LoamMapping::reset() {
  edge_map_.clear();
  planar_map_.clear();
  edge_tree_ = KdTree3f();
  planar_tree_ = KdTree3f();
}

std::vector<Constraint> LoamMapping::associate(const PointCloud& edges, const PointCloud& planars, const SE3& T) const {
  std::vector<Constraint> cs;
  cs.reserve(edges.size() + planars.size());
  Constraint c;
  for (const auto& p : edges.points) {
    const Eigen::Vector3d q = T * p.cast<double>();
    if (edge_correspondence(edge_tree_, q, 1.0, q, p_.association, c)) cs.push_back(c);
  }
  for (const auto& p : planars.points) {
    const Eigen::Vector3d q = T * p.cast<double>();
    if (planar_correspondence(planar_tree_, q, 1.0, q, p_.association, c)) cs.push_back(c);
  }
  return cs;
}

void LoamMapping::insert(const PointCloud& edges, const PointCloud& planars, const SE3& T) {
  for (const auto& p : edges.points) edge_map_.insert((T * p.cast<double>()).cast<float>());
  for (const auto& p : planars.points) planar_map_.insert((T * p.cast<double>()).cast<float>());
  const Eigen::Vector3f centre = T.translation().cast<float>();
  edge_map_.crop(centre, p_.map_radius_m);
  planar_map_.crop(centre, p_.map_radius_m);
  edge_tree_ = KdTree3f(edge_map_.points());
  planar_tree_ = KdTree3f(planar_map_.points());
}

MappingResult LoamMapping::process(const PointCloud& edges, const PointCloud& planars, const SE3& guess) {
  MappingResult res;
  res.T_world_lidar = guess;
  SE3 T = guess;
  for (int round = 0; round < p_.correspondence_rounds && map_size() > 0; ++round) {
    // The points already carry T; the solve finds a small correction in world-aligned axes
    // about the LiDAR's position (LOAM's parameterisation). Rotating about the world origin
    // instead couples every rotation with a translation of |t| times it, so the degeneracy test
    // and the damping would change with the distance from the start.
    std::vector<Constraint> cs = associate(edges, planars, T);
    res.constraints = cs.size();
    if (cs.size() < p_.min_constraints) break;
    const Eigen::Vector3d centre = T.translation();
    for (auto& c : cs) {
      c.point -= centre;
      c.anchor -= centre;
    }
    const LmSolution sol = solve_lm(cs, Vector6d::Zero(), p_.lm);
    if (!sol.x.allFinite()) break;
    const SE3 step = motion_to_se3(sol.x);
    T.linear() = step.linear() * T.linear();
    T.translation() += step.translation();
    res.matched = sol.inliers >= p_.min_constraints;
    res.degenerate_dims = sol.degenerate_dims;
    res.inliers = sol.inliers;
    res.rms_m = sol.rms_m;
    if (sol.x.head<3>().norm() < 1e-4 && sol.x.tail<3>().norm() < 1e-5) break;
  }
  if (res.matched) res.T_world_lidar = T;
  insert(edges, planars, res.T_world_lidar);
  return res;
}

}  // namespace bipednav::localization
