#pragma once

#include <optional>
#include <string>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/localization/loam_features.hpp"
#include "bipednav/localization/loam_mapping.hpp"
#include "bipednav/localization/loam_odometry.hpp"

namespace bipednav::localization {

struct LoamParams {
  FeatureParams features{};
  OdometryParams odometry{};
  MappingParams mapping{};
  std::size_t min_features = 20;  // fewer edge + planar points: the sweep is featureless
  // Without a motion prior the guess is the previous sweep's motion minus its height, roll and pitch
  // rates: those are weakly observed (a torso VLP-16 barely sees the floor) and a rate kept from
  // one noisy sweep would otherwise make the height drift at a constant speed.
  bool planar_constant_velocity = true;
  // With motion priors on two consecutive sweeps, the odometry projects the previous sweep with
  // this sweep's motion plus the change between the two priors' rotations (LoamOdometry::estimate's
  // reference_offset) instead of assuming constant velocity. A change larger than these bounds (an
  // odometry glitch) is ignored.
  bool reference_from_prior_change = false;
  double max_prior_change_m = 0.1;
  double max_prior_change_rad = 0.15;
  // The change is right only while the odometry's error stays the same: with e = prior - LOAM's
  // estimate on a sweep, the change's error is e(previous sweep) - e(this sweep). A constant scale
  // or bias error cancels; a slip starting or ending does not (the change would trust the odometry
  // exactly when it is wrong). When the rotations of the two errors differ by more than this, or
  // the previous sweep has no estimate to compare with, the sweep is estimated again with constant
  // velocity. Closed-loop noise of that difference: p95 0.009 rad (turtlebot3, hexagon_static;
  // digit, three_rooms, incl. torso sway); a 0.3 slip at 1 rad/s makes it 0.07 rad.
  double max_prior_error_change_rad = 0.02;
  // A robot on a flat floor: the LiDAR's height, roll and pitch stay those of the anchor pose
  // (T_world_lidar_initial or set_pose), so every odometry and mapping result is projected onto
  // x, y and yaw. Height and tilt are the directions a torso-mounted VLP-16 observes worst (it
  // sees the floor only far away); left free they drift and pull x/y with them (LeGO-LOAM
  // constrains them from the ground for the same reason).
  bool planar_motion = false;
  SE3 T_world_lidar_initial = SE3::Identity();  // anchors the first sweep in the world (map) frame
  // Fill LoamOutput::deskewed (the whole sweep moved to its end pose). Off where only the pose is
  // read (the navigator's Localizer): the de-skew does not feed the pose.
  bool output_deskewed = true;
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp). T_world_lidar_initial and output_deskewed are left out:
  // the Localizer sets them.
  template <class V>
  void visit_fields(V& v) {
    v.group("features", features);
    v.group("odometry", odometry);
    v.group("mapping", mapping);
    v("min_features", min_features);
    v("planar_constant_velocity", planar_constant_velocity);
    v("reference_from_prior_change", reference_from_prior_change);
    v("max_prior_change_m", max_prior_change_m);
    v("max_prior_change_rad", max_prior_change_rad);
    v("max_prior_error_change_rad", max_prior_error_change_rad);
    v("planar_motion", planar_motion);
  }
};

struct LoamOutput {
  SE3 T_world_lidar = SE3::Identity();  // at the sweep end; world = the first sweep's LiDAR frame
                                        // (moved by T_world_lidar_initial)
  bool healthy = true;                  // false: the pose is a prediction only (see reason)
  std::string reason;                   // empty when healthy and well constrained
  bool degenerate = false;              // some directions came from the motion prior, not the scan
  double odometry_ms = 0.0;             // features + odometry + de-skew
  double mapping_ms = 0.0;              // 0 on sweeps without a mapping step
  PointCloud deskewed;                  // the valid points in the LiDAR frame at the sweep end
                                        // (empty unless LoamParams::output_deskewed)
  SE3 T_prev_lidar = SE3::Identity();   // estimated LiDAR motion since the previous sweep
  bool mapped = false;                  // a mapping step ran on this sweep
  // The projector onto the horizontal world directions this sweep's mapping step could not observe:
  // they come from the motion prior (wheel or leg odometry) or constant velocity. Zero when the map
  // observed x and y; the identity on sweeps without a matched mapping step.
  Eigen::Matrix2d unobserved_xy = Eigen::Matrix2d::Identity();
  bool prior_change_used = false;  // the reference was projected with the (checked) prior change
  std::size_t edge_features = 0, planar_features = 0;
};

// LiDAR odometry and mapping (section 4.4): odometry at the sweep rate, mapping at
// mapping.rate_hz, their transforms combined into a pose at the sweep rate.
class Loam {
 public:
  explicit Loam(LoamParams p = {});

  // One sweep in the LiDAR frame with per-point time offsets (since the sweep start) and rings.
  // `motion_prior` is the LiDAR motion since the previous sweep from another odometry source
  // (T_prevlidar_lidar); without it a constant-velocity guess is used.
  // `up_in_lidar` is the world's up direction in the LiDAR frame at the sweep end from an IMU
  // (gravity): the mapping step holds roll and pitch to it (MappingParams::gravity_weight).
  LoamOutput process(const PointCloud& sweep, const std::optional<SE3>& motion_prior = std::nullopt,
                     const std::optional<Eigen::Vector3d>& up_in_lidar = std::nullopt);
  void reset();
  // Re-anchors the current pose (e.g. after a relocalization); the map is cleared.
  void set_pose(const SE3& T_world_lidar);
  const LoamParams& params() const { return p_; }
  std::size_t map_size() const { return mapping_.map_size(); }

 private:
  SE3 odometry_step(const LoamFeatures& f, const SE3& guess, bool prior_given, const Vector6d& reference_offset,
                    LoamOutput& out);
  std::optional<Vector6d> reference_offset(const std::optional<SE3>& prior) const;  // none: constant velocity
  bool prior_error_steady(const SE3& prior, const SE3& estimate) const;
  void mapping_step(LoamOutput& out, const std::optional<Eigen::Vector3d>& up_in_lidar);
  SE3 constant_velocity_guess() const;
  SE3 level(const SE3& T_world_lidar) const;  // the planar projection (identity without planar_motion)

  LoamParams p_;
  FeatureScratch feature_scratch_;  // extract_features' work space
  LoamOdometry odometry_;
  LoamMapping mapping_;
  std::size_t sweeps_ = 0;
  std::size_t mapping_every_ = 10;
  SE3 last_motion_ = SE3::Identity();
  std::optional<Vector6d> last_prior_;        // the previous sweep's motion prior, when it had one
  std::optional<Vector6d> last_prior_error_;  // ... minus its matched odometry estimate
  SE3 T_odom_lidar_ = SE3::Identity();        // accumulated odometry
  SE3 T_world_odom_ = SE3::Identity();        // correction from the last mapping step
  SE3 last_good_ = SE3::Identity();
  SE3 anchor_ = SE3::Identity();  // height, roll and pitch for planar_motion
};

// `T` with the height, roll and pitch of `anchor` (x, y and the yaw of `T` about the anchor's tilt kept).
SE3 project_to_plane(const SE3& T, const SE3& anchor);

}  // namespace bipednav::localization
