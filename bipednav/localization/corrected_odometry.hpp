#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/common/sensor_frame.hpp"
#include "bipednav/localization/gicp.hpp"

namespace bipednav::localization {

// Kinematic odometry corrected by GICP between consecutive depth clouds (second reference,
// section III).
struct CorrectedOdometryParams {
  GicpParams gicp{};
  double ground_band_m = 0.05;         // points below this height in the odometry frame are removed
  std::size_t min_points = 50;         // fewer points after ground removal: no correction this time
  double max_correction_step_m = 0.3;  // a larger change of T_corr in one update is rejected
  double max_correction_step_rad = 0.2;
  double max_fitness_m2 = 0.05;  // worse mean squared match distance is rejected
  // A direction of (x, y, yaw) is corrected only when its GICP information equals that of this
  // fraction of the matches lying on surfaces facing it; otherwise it keeps the odometry.
  // 0 corrects every direction.
  double min_constraining_fraction = 0.003;
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v.group("gicp", gicp);
    v("ground_band_m", ground_band_m);
    v("min_points", min_points);
    v("max_correction_step_m", max_correction_step_m);
    v("max_correction_step_rad", max_correction_step_rad);
    v("max_fitness_m2", max_fitness_m2);
    v("min_constraining_fraction", min_constraining_fraction);
  }
};

// The GICP information (Gauss-Newton Hessian of the Mahalanobis cost) of source matched into
// target at T_target_source, over a planar motion (x, y, yaw about `pivot`) of the target frame.
// The correspondences are each source point's nearest target point within max_correspondence_m.
Eigen::Matrix3d planar_information(const GicpCloud& source, const GicpCloud& target, const SE3& T_target_source,
                                   const Eigen::Vector3d& pivot, double max_correspondence_m);
// The same with the correspondences given: matches[i] is the target point of source point i or
// kGicpNoMatch (gicp_align's `matches` at T_target_source).
Eigen::Matrix3d planar_information(const GicpCloud& source, const GicpCloud& target, const SE3& T_target_source,
                                   const Eigen::Vector3d& pivot, const std::vector<std::uint32_t>& matches);

struct CorrectionUpdate {
  SE3 T_corrected_base = SE3::Identity();  // T_corr^t * T_odom^t (base frame)
  SE3 T_corr = SE3::Identity();            // the correction of eq. 1
  bool corrected = false;                  // false: the correction was kept from the last update
  int degenerate_directions = 0;           // directions of (x, y, yaw) left to the odometry
  std::string reason;                      // why not, when not
  GicpResult gicp;
};

class CorrectedOdometry {
 public:
  CorrectedOdometry(CorrectedOdometryParams p, const SE3& T_base_sensor);

  // One depth cloud (sensor frame) with the odometry pose of the same instant. Solves eq. 1,
  //   T_corr^t = argmin_T' sum_i | T_corr^{t-1} T_odom^{t-1} q_i - T' T_odom^t p_i |^2,
  // by GICP initialised with T_corr^{t-1}; the corrected pose is T_corr^t T_odom^t.
  CorrectionUpdate update(const SE3& T_odom_base, const PointCloud& cloud_sensor);
  const SE3& correction() const { return T_corr_; }
  void reset();

 private:
  // The GICP result with its poorly constrained planar directions reset to the last correction;
  // `pairs` are its correspondences at that result (gicp_align's `matches`).
  SE3 constrained_correction(const GicpCloud& current, const SE3& T_odom_base, const std::vector<std::uint32_t>& pairs,
                             CorrectionUpdate& u) const;

  CorrectedOdometryParams p_;
  SE3 T_base_sensor_;
  SE3 T_corr_ = SE3::Identity();
  std::optional<GicpCloud> previous_;  // T_corr^{t-1} T_odom^{t-1} q_i: the last cloud, corrected
};

}  // namespace bipednav::localization
