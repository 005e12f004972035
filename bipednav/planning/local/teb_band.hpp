#pragma once

#include <Eigen/Core>
#include <vector>

#include "bipednav/common/path.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/planning/local/teb_params.hpp"

namespace bipednav::planning::local {

// The timed elastic band: poses s_k = (x, y, theta) and the intervals dT_k between s_k and s_{k+1}
// (dt_s.size() == poses.size() - 1).
struct TebBand {
  std::vector<Pose2> poses;
  std::vector<double> dt_s;

  std::size_t size() const { return poses.size(); }
  bool empty() const { return poses.empty(); }
  double duration_s() const;
  // The band as a timed path (times since the first pose).
  Path to_path(const std::string& frame_id = "map") const;
};

// Initialises the band along the polyline start -> via points -> goal, spaced so that each interval
// takes about dt_ref at max_vel (at least min_samples poses). Intermediate headings follow the
// polyline; the first and last pose keep the start and goal orientation.
TebBand init_band(const Pose2& start, const std::vector<Eigen::Vector2d>& via, const Pose2& goal,
                  const TebLimits& limits, const TebBandParams& params);

// Re-samples the band (thesis 5.2): inserts a pose where dT_k > dT_ref + hyst, removes one where
// dT_k < dT_ref - hyst, never below min_samples or above max_samples. Returns true when changed.
bool resample_band(TebBand& band, const TebBandParams& params);

// Warm start from the previous cycle: drops the poses the robot has passed, moves the first pose to
// the robot and the last one to the new goal. Returns false (band untouched) when the goal jumped
// too far and the band must be re-initialised.
bool warm_start_band(TebBand& band, const Pose2& start, const Pose2& goal, const TebBandParams& params);

}  // namespace bipednav::planning::local
