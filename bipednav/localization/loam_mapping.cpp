#include "bipednav/localization/loam_mapping.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::localization {

void MappingParams::validate() const {
  require(edge_leaf_m > 0.0 && planar_leaf_m > 0.0, "edge_leaf_m/planar_leaf_m", "> 0");
  require(map_radius_m > 0.0, "map_radius_m", "> 0");
  association.validate();
  require(correspondence_rounds >= 1, "correspondence_rounds", ">= 1");
  require(round_converged_translation_m > 0.0, "round_converged_translation_m", "> 0");
  require(round_converged_rotation_rad > 0.0, "round_converged_rotation_rad", "> 0");
  require(min_constraints >= 6, "min_constraints", ">= 6");
  require(gravity_weight >= 0.0, "gravity_weight", ">= 0");
  lm.validate();
}

std::int64_t VoxelPointMap::key(const Eigen::Vector3f& p, const Eigen::Vector3f& viewpoint) const {
  const auto cell = [&](float v) {
    return (static_cast<std::int64_t>(std::floor(v / leaf_m_)) + (1 << 19)) & ((1 << 20) - 1);
  };
  const Eigen::Vector3f d = viewpoint - p;
  Eigen::Index axis = 0;
  d.cwiseAbs().maxCoeff(&axis);
  const std::int64_t direction = 2 * axis + (d(axis) < 0.0f ? 1 : 0);  // 0..5
  return (direction << 60) | (cell(p.x()) << 40) | (cell(p.y()) << 20) | cell(p.z());
}

void VoxelPointMap::insert(const Eigen::Vector3f& p, const Eigen::Vector3f& viewpoint) {
  if (!occupied_.insert(key(p, viewpoint)).second) return;
  points_.push_back(p);
  viewpoints_.push_back(viewpoint);
}

void VoxelPointMap::crop(const Eigen::Vector3f& centre, double radius_m) {
  const float r2 = static_cast<float>(radius_m * radius_m);
  std::vector<std::size_t> kept;
  kept.reserve(points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i)
    if ((points_[i] - centre).squaredNorm() <= r2) kept.push_back(i);
  if (kept.size() == points_.size()) return;
  const std::vector<Eigen::Vector3f> points = std::move(points_), viewpoints = std::move(viewpoints_);
  clear();
  for (const std::size_t i : kept) insert(points[i], viewpoints[i]);
}

void VoxelPointMap::clear() {
  points_.clear();
  viewpoints_.clear();
  occupied_.clear();
}

LoamMapping::LoamMapping(MappingParams p) : p_(std::move(p)), edge_map_(p_.edge_leaf_m), planar_map_(p_.planar_leaf_m) {
  p_.validate();
}

void LoamMapping::reset() {
  edge_map_.clear();
  planar_map_.clear();
  edge_tree_ = PointKdTree();
  planar_tree_ = PointKdTree();
  edge_hints_.clear();
  planar_hints_.clear();
}

std::vector<Constraint> LoamMapping::associate(const PointCloud& edges, const PointCloud& planars, const SE3& T) {
  std::vector<Constraint> cs;
  cs.reserve(edges.size() + planars.size());
  Constraint c;
  const ViewCheck edge_view{&edge_map_.viewpoints(), T.translation()};
  const ViewCheck planar_view{&planar_map_.viewpoints(), T.translation()};
  // Each point's neighbours of the previous round bound its next search (see NeighbourHint).
  edge_hints_.resize(edges.size());
  planar_hints_.resize(planars.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const Eigen::Vector3d q = T * edges.points[i].cast<double>();
    if (edge_correspondence(edge_tree_, q, 1.0, q, p_.association, c, &edge_view, &edge_hints_[i])) cs.push_back(c);
  }
  for (std::size_t i = 0; i < planars.size(); ++i) {
    const Eigen::Vector3d q = T * planars.points[i].cast<double>();
    if (planar_correspondence(planar_tree_, q, 1.0, q, p_.association, c, &planar_view, &planar_hints_[i]))
      cs.push_back(c);
  }
  return cs;
}

void LoamMapping::insert(const PointCloud& edges, const PointCloud& planars, const SE3& T) {
  const Eigen::Vector3f centre = T.translation().cast<float>();
  for (const auto& p : edges.points) edge_map_.insert((T * p.cast<double>()).cast<float>(), centre);
  for (const auto& p : planars.points) planar_map_.insert((T * p.cast<double>()).cast<float>(), centre);
  edge_map_.crop(centre, p_.map_radius_m);
  planar_map_.crop(centre, p_.map_radius_m);
  edge_tree_.build(edge_map_.points());
  planar_tree_.build(planar_map_.points());
}

namespace {

// Rows x, y of exp(dtheta) R u - e_z, linear in dtheta: the up direction u the IMU measured,
// rotated into the world by the corrected pose, must point up.
LinearPrior gravity_prior(const SE3& T, const std::optional<Eigen::Vector3d>& up_in_lidar, double weight) {
  LinearPrior prior;
  if (!up_in_lidar || !up_in_lidar->allFinite() || up_in_lidar->norm() < 1e-6 || weight <= 0.0) return prior;
  const Eigen::Vector3d v = T.linear() * up_in_lidar->normalized();
  prior.A = Eigen::Matrix<double, 2, 6>::Zero();
  prior.A.block<2, 3>(0, 3) << 0.0, v.z(), -v.y(), -v.z(), 0.0, v.x();
  prior.b = v.head<2>();
  prior.weight = weight;
  return prior;
}

}  // namespace

MappingResult LoamMapping::process(const PointCloud& edges, const PointCloud& planars, const SE3& guess,
                                   const std::optional<Eigen::Vector3d>& up_in_lidar) {
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
    const LmSolution sol = solve_lm(cs, Vector6d::Zero(), p_.lm, gravity_prior(T, up_in_lidar, p_.gravity_weight));
    if (!sol.x.allFinite()) break;
    const SE3 step = motion_to_se3(sol.x);
    T.linear() = step.linear() * T.linear();
    T.translation() += step.translation();
    res.matched = sol.inliers >= p_.min_constraints;
    res.degenerate_dims = sol.degenerate_dims;
    res.unobserved_xy = horizontal_weak_projector(sol.degenerate_directions, sol.degenerate_dims);
    res.inliers = sol.inliers;
    res.rms_m = sol.rms_m;
    if (sol.x.head<3>().norm() < p_.round_converged_translation_m &&
        sol.x.tail<3>().norm() < p_.round_converged_rotation_rad)
      break;
  }
  if (res.matched) res.T_world_lidar = T;
  insert(edges, planars, res.T_world_lidar);
  return res;
}

}  // namespace bipednav::localization
