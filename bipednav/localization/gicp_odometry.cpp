#include "bipednav/localization/gicp_odometry.hpp"

#include "bipednav/common/clock.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::localization {

void GicpOdometryParams::validate() const {
  gicp.validate();
  require(min_points >= static_cast<std::size_t>(gicp.covariance_neighbours), "min_points",
          ">= gicp.covariance_neighbours");
}

GicpOdometry::GicpOdometry(GicpOdometryParams p, const SE3& T_world_lidar_initial)
    : p_(std::move(p)), T_world_lidar_(T_world_lidar_initial) {
  p_.validate();
  if (!T_world_lidar_.matrix().allFinite()) throw Error("GicpOdometry: the initial pose is not finite");
}

GicpOdometryOutput GicpOdometry::process(const PointCloud& sweep) {
  Stopwatch sw;
  GicpOdometryOutput out;
  const bool first = sweeps_ == 0;
  GicpCloud current = prepare_gicp_cloud(sweep, p_.gicp);
  SE3 motion = last_motion_;
  if (current.size() < p_.min_points) {
    out.healthy = first;
    previous_.reset();  // the next sweep starts over from the guess
  } else {
    if (previous_) {
      out.gicp = gicp_align(current, *previous_, last_motion_, p_.gicp);
      // Not converged within max_iterations: the last iterate is kept (it is still finite), flagged.
      out.healthy = out.gicp.converged;
      if (out.gicp.T_target_source.matrix().allFinite()) motion = out.gicp.T_target_source;
    } else {
      out.healthy = first;
    }
    previous_ = std::move(current);
  }
  if (!first) {
    T_world_lidar_ = T_world_lidar_ * motion;
    last_motion_ = motion;
  }
  ++sweeps_;
  out.T_prev_lidar = first ? SE3::Identity() : motion;
  out.T_world_lidar = T_world_lidar_;
  out.time_ms = sw.elapsed_ms();
  return out;
}

}  // namespace bipednav::localization
