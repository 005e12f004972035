#pragma once

#include <Eigen/Core>
#include <vector>

#include "bipednav/common/twist.hpp"
#include "bipednav/planning/local/costmap_obstacles.hpp"
#include "bipednav/planning/local/teb_band.hpp"
#include "bipednav/planning/local/teb_params.hpp"
#include "bipednav/planning/local/teb_residuals.hpp"

namespace bipednav::planning::local {

// What the optimiser needs besides the band itself.
struct TebProblemInput {
  const std::vector<Obstacle>* obstacles = nullptr;  // may be null: no obstacles
  std::vector<Eigen::Vector2d> via_points;           // global-path attraction (may be empty)
  Twist start_velocity;                              // for the first acceleration term
  // Moving obstacles, used with TebOptimizerParams::dynamic_obstacles (may be null; entries with
  // non-finite values or a negative clearance are ignored).
  const std::vector<TebMovingObstacle>* moving = nullptr;
};

// The objective (eq. 5.21) split by term, with the base weights, for candidate selection and tests.
struct BandCost {
  double time = 0.0;        // sum dT^2 (weighted)
  double kinematics = 0.0;  // non-holonomic + backwards
  double velocity = 0.0;
  double acceleration = 0.0;
  double obstacle = 0.0;
  double viapoint = 0.0;
  double dynamic_obstacle = 0.0;  // with dynamic_obstacles
  double duration_s = 0.0;
  double min_obstacle_dist_m = 1e9;  // over the inner poses
  double max_nh_error = 0.0;         // largest |h_k| of eq. 5.6 (m)
  // With dynamic_obstacles: smallest distance of an inner pose to a moving obstacle's predicted edge at the
  // pose's time (centre distance minus its radius).
  double min_dynamic_dist_m = 1e9;

  // Selection cost: the objective without the via-point term, so that bands of other homotopy
  // classes (which deviate from the global path on purpose) compete fairly.
  double selection() const { return duration_s + kinematics + velocity + acceleration + obstacle + dynamic_obstacle; }
};

// Evaluates the band's penalty terms with the base weights.
BandCost evaluate_band(const TebBand& band, const TebProblemInput& input, const TebLimits& limits,
                       const TebOptimizerParams& params);

// The moving obstacles of the input the band is optimised against: none unless params.dynamic_obstacles,
// and only the usable ones.
std::vector<TebMovingObstacle> band_moving_obstacles(const TebProblemInput& input, const TebOptimizerParams& params);
// Each pose's time from the band's start (the sum of the dT before it), capped at max_s.
std::vector<double> band_pose_times(const std::vector<double>& dt_s, double max_s);

// Optimises the band in place (eq. 5.20): no_outer_iterations Levenberg-Marquardt solves of
// no_inner_iterations each, re-sampling the band and re-associating the nearest obstacles before
// each solve and scaling the obstacle and kinematics weights up after each. The first and the last
// pose stay fixed. Returns false if the solver failed (the band is then left as it was).
bool optimize_band(TebBand& band, const TebProblemInput& input, const TebLimits& limits,
                   const TebBandParams& band_params, const TebOptimizerParams& params);

}  // namespace bipednav::planning::local
