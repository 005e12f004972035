#pragma once

#include <cstdint>
#include <optional>
#include <unordered_set>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/localization/feature_association.hpp"
#include "bipednav/localization/point_kdtree.hpp"
#include "bipednav/localization/registration_lm.hpp"

namespace bipednav::localization {

// LiDAR mapping of LOAM (section 4.4.4).
struct MappingParams {
  double rate_hz = 1.0;      // mapping rate; <= 0 maps every sweep
  double edge_leaf_m = 0.2;  // map down-sampling (one point per voxel)
  double planar_leaf_m = 0.4;
  double map_radius_m = 60.0;  // map points farther than this from the LiDAR are dropped
  AssociationParams association{.neighbours = 5,
                                .max_correspondence_m = 1.0,
                                .max_plane_deviation_m = 0.2,
                                .min_line_ratio = 3.0,
                                .edge_weight = 0.3};
  int correspondence_rounds = 5;
  // The rounds stop once a round's correction is below both of these (as OdometryParams').
  double round_converged_translation_m = 1e-4;
  double round_converged_rotation_rad = 1e-5;
  std::size_t min_constraints = 30;
  // Weight of a gravity (IMU tilt) measurement in units of full-weight point rows, rad vs m. The
  // map alone pins roll and pitch only as well as the map was built: each new room is inserted at
  // the tilt of the pose that first saw it, so tilt errors persist and turn into height and x/y
  // drift. An IMU measures tilt absolutely (LOAM fuses it into the mapping step, LeGO-LOAM and
  // LIO-SAM likewise).
  double gravity_weight = 1000.0;
  LmParams lm{};
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("rate_hz", rate_hz);
    v("edge_leaf_m", edge_leaf_m);
    v("planar_leaf_m", planar_leaf_m);
    v("map_radius_m", map_radius_m);
    v.group("association", association);
    v("correspondence_rounds", correspondence_rounds);
    v("round_converged_translation_m", round_converged_translation_m);
    v("round_converged_rotation_rad", round_converged_rotation_rad);
    v("min_constraints", min_constraints);
    v("gravity_weight", gravity_weight);
    v.group("lm", lm);
  }
};

struct MappingResult {
  SE3 T_world_lidar = SE3::Identity();
  bool matched = false;  // false: the map was empty or too few correspondences (guess kept)
  int degenerate_dims = 0;
  // The projector onto the horizontal world directions the match could not observe (kept from the
  // guess, see horizontal_weak_projector); zero when it observes x and y.
  Eigen::Matrix2d unobserved_xy = Eigen::Matrix2d::Zero();
  std::size_t constraints = 0;
  std::size_t inliers = 0;
  double rms_m = 0.0;
};

// A point set down-sampled incrementally: a point is added only when its voxel is still empty.
// Each point keeps the sensor position it was seen from, and a voxel holds one point per viewing
// direction (the dominant axis and sign of point -> sensor): the two faces of a wall thinner than
// a voxel both stay in the map.
class VoxelPointMap {
 public:
  explicit VoxelPointMap(double leaf_m = 0.2) : leaf_m_(leaf_m) {}
  void insert(const Eigen::Vector3f& p, const Eigen::Vector3f& viewpoint);
  // Drops points farther than radius_m from centre.
  void crop(const Eigen::Vector3f& centre, double radius_m);
  const std::vector<Eigen::Vector3f>& points() const { return points_; }
  const std::vector<Eigen::Vector3f>& viewpoints() const { return viewpoints_; }
  std::size_t size() const { return points_.size(); }
  void clear();

 private:
  std::int64_t key(const Eigen::Vector3f& p, const Eigen::Vector3f& viewpoint) const;
  double leaf_m_;
  std::vector<Eigen::Vector3f> points_, viewpoints_;
  std::unordered_set<std::int64_t> occupied_;
};

class LoamMapping {
 public:
  explicit LoamMapping(MappingParams p);

  // Registers the de-skewed features of one sweep (LiDAR frame at the sweep end) onto the map,
  // starting from `T_world_lidar_guess`, then inserts them at the registered pose. The first call
  // only inserts.
  // `up_in_lidar`: the world's up direction in the LiDAR frame measured by an IMU, if there is one.
  MappingResult process(const PointCloud& edges, const PointCloud& planars, const SE3& T_world_lidar_guess,
                        const std::optional<Eigen::Vector3d>& up_in_lidar = std::nullopt);
  std::size_t map_size() const { return edge_map_.size() + planar_map_.size(); }
  void reset();
  const MappingParams& params() const { return p_; }

 private:
  std::vector<Constraint> associate(const PointCloud& edges, const PointCloud& planars, const SE3& T);
  void insert(const PointCloud& edges, const PointCloud& planars, const SE3& T);

  MappingParams p_;
  VoxelPointMap edge_map_, planar_map_;
  PointKdTree edge_tree_, planar_tree_;
  // Each point's neighbours of the previous round, and their fit, for the trees above (see
  // NeighbourHint): kept between rounds for reuse.
  std::vector<NeighbourHint> edge_hints_, planar_hints_;
};

}  // namespace bipednav::localization
