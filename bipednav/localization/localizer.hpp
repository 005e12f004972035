#pragma once

#include <Eigen/Core>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/sensor_frame.hpp"
#include "bipednav/localization/loam.hpp"

namespace bipednav::localization {

struct LocalizerParams {
  std::string method = "loam";  // loam | odometry
  localization::LoamParams loam;
  double sweep_duration_s = 0.1;       // a LiDAR sweep's span (stamp = its start)
  double max_correction_jump_m = 0.5;  // a LOAM pose this far from the odometry prediction is rejected
  double max_correction_jump_rad = 0.35;
  int unhealthy_after_bad_sweeps = 5;  // consecutive rejected/unhealthy sweeps before reporting bad health
  double odometry_timeout_s = 0.5;
  // Odometry moving faster than this between two sweeps has jumped (an estimator reset, a
  // glitch): LOAM then runs without the odometry prior and its pose is taken as it is.
  double max_odometry_speed_mps = 1.0;
  double max_odometry_rate_radps = 2.0;
  // The position's uncertainty: the odometry's error grows as this share of the distance travelled
  // (scale and heading biases make dead-reckoning error grow in proportion to distance, not its
  // square root), and a direction the LOAM map match observes is known to scan_position_sigma_m.
  double odometry_drift_ratio = 0.03;
  double scan_position_sigma_m = 0.02;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("method", method);
    v.group("loam", loam);
    v("sweep_duration_s", sweep_duration_s);
    v("max_correction_jump_m", max_correction_jump_m);
    v("max_correction_jump_rad", max_correction_jump_rad);
    v("unhealthy_after_bad_sweeps", unhealthy_after_bad_sweeps);
    v("odometry_timeout_s", odometry_timeout_s);
    v("max_odometry_speed_mps", max_odometry_speed_mps);
    v("max_odometry_rate_radps", max_odometry_rate_radps);
    v("odometry_drift_ratio", odometry_drift_ratio);
    v("scan_position_sigma_m", scan_position_sigma_m);
  }
};

// Pose estimation for the navigator: the map -> odom correction from LOAM (section 4.4), applied
// to the odometry stream between sweeps so the pose is available at every tick (REP-105:
// T_map_base = T_map_odom * T_odom_base). With method "odometry" the correction stays fixed.
class Localizer {
 public:
  Localizer(LocalizerParams params, const RobotProfile& robot, const Pose2& T_map_base_initial);

  void add_odometry(const Odometry& odom);
  // One LiDAR sweep in the lidar frame (time offsets since sweep.stamp_s, rings).
  void add_sweep(const PointCloud& sweep);

  Pose2 T_map_base() const { return correction_ * odom_now_; }
  Pose2 T_map_odom() const { return correction_; }
  Twist velocity() const { return velocity_; }
  bool healthy(double now_s) const;
  const std::string& reason() const { return reason_; }
  std::size_t odometry_jumps() const { return odometry_jumps_; }  // absorbed by re-anchoring on LOAM
  // The position estimate's standard deviation along a map direction (normalised here), in m.
  // Directions the map matches observe stay at scan_position_sigma_m; a direction LOAM leaves to
  // the odometry (open ground, a long corridor; or no LiDAR) grows with the distance travelled.
  double position_sigma_m(const Eigen::Vector2d& direction_map) const;
  // The largest of those and its direction (unit, map frame).
  double weakest_position_sigma_m(Eigen::Vector2d* direction_map = nullptr) const;
  // Forces a pose (initial pose / relocalization); LOAM re-anchors at the next sweep.
  void reset(const Pose2& T_map_base);

 private:
  std::optional<Pose2> odom_at(double t_s) const;
  bool plausible_odometry_motion(const Pose2& delta, double dt_s) const;

  LocalizerParams params_;
  SE3 T_base_lidar_ = SE3::Identity();
  bool has_lidar_ = false;
  std::unique_ptr<Loam> loam_;
  std::deque<Odometry> history_;
  Pose2 odom_now_;
  Twist velocity_;
  Pose2 correction_;  // T_map_odom
  // The position's deviation matrix S (m, map frame; covariance S^2): grows by
  // odometry_drift_ratio per metre, is reset where the map observes.
  Eigen::Matrix2d position_deviation_;
  std::optional<Pose2> prev_sweep_odom_;
  double prev_sweep_end_s_ = 0.0;
  std::size_t odometry_jumps_ = 0;
  int bad_sweeps_ = 0;
  std::string reason_;
  double last_odom_s_ = -1.0;
  bool anchored_ = false;
};

}  // namespace bipednav::localization
