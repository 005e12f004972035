#include "bipednav/planning/local/moving_obstacle_params.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::planning::local {

namespace {

bool positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

void MovingObstacleParams::validate() const {
  require(positive(cluster_cell_m), "moving_obstacles.cluster_cell_m", "> 0");
  require(min_points >= 1, "moving_obstacles.min_points", ">= 1");
  require(positive(max_blob_radius_m), "moving_obstacles.max_blob_radius_m", "> 0");
  require(positive(max_range_m), "moving_obstacles.max_range_m", "> 0");
  require(positive(gate_m), "moving_obstacles.gate_m", "> 0");
  require(std::isfinite(vacated_radius_m) && vacated_radius_m >= 0.0, "moving_obstacles.vacated_radius_m", ">= 0");
  require(positive(max_track_age_s), "moving_obstacles.max_track_age_s", "> 0");
  require(positive(measurement_noise_m), "moving_obstacles.measurement_noise_m", "> 0");
  require(positive(accel_noise_mps2), "moving_obstacles.accel_noise_mps2", "> 0");
  require(positive(max_speed_mps), "moving_obstacles.max_speed_mps", "> 0");
  require(min_hits >= 1, "moving_obstacles.min_hits", ">= 1");
  require(std::isfinite(min_moving_speed_mps) && min_moving_speed_mps >= 0.0, "moving_obstacles.min_moving_speed_mps",
          ">= 0");
  require(std::isfinite(min_displacement_m) && min_displacement_m >= 0.0, "moving_obstacles.min_displacement_m",
          ">= 0");
  require(std::isfinite(latch_displacement_m) && latch_displacement_m >= 0.0, "moving_obstacles.latch_displacement_m",
          ">= 0");
  require(positive(max_prediction_s), "moving_obstacles.max_prediction_s", "> 0");
  require(std::isfinite(global_map_margin_m) && global_map_margin_m >= 0.0, "moving_obstacles.global_map_margin_m",
          ">= 0");
  require(positive(max_coast_s), "moving_obstacles.max_coast_s", "> 0");
  require(std::isfinite(radius_floor_window_s) && radius_floor_window_s >= 0.0,
          "moving_obstacles.radius_floor_window_s", ">= 0");
  require(std::isfinite(reacquire_gate_m) && reacquire_gate_m >= 0.0, "moving_obstacles.reacquire_gate_m", ">= 0");
  require(std::isfinite(recurrence_history_s) && recurrence_history_s >= 0.0, "moving_obstacles.recurrence_history_s",
          ">= 0");
  require(positive(recurrence_match_m), "moving_obstacles.recurrence_match_m", "> 0");
  require(positive(recurrence_min_lag_s), "moving_obstacles.recurrence_min_lag_s", "> 0");
  require(std::isfinite(coast_max_growth_m) && coast_max_growth_m >= 0.0, "moving_obstacles.coast_max_growth_m",
          ">= 0");
}

}  // namespace bipednav::planning::local
