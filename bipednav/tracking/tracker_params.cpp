#include "bipednav/tracking/tracker_params.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::tracking {

namespace {

bool tracker_positive(double v) { return std::isfinite(v) && v > 0.0; }
bool tracker_non_negative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

MotionModel parse_motion_model(const std::string& name) {
  if (name == "cv") return MotionModel::kConstantVelocity;
  if (name == "imm") return MotionModel::kImmCvCt;
  throw ParamError("tracking.motion_model", "cv or imm, got '" + name + "'");
}

void TrackerParams::validate() const {
  require(tracker_non_negative(static_margin_m), "tracking.static_margin_m", ">= 0");
  require(tracker_non_negative(static_age_s), "tracking.static_age_s", ">= 0");
  require(tracker_non_negative(static_gap_s), "tracking.static_gap_s", ">= 0");
  require(tracker_non_negative(persistent_span_s), "tracking.persistent_span_s", ">= 0");
  require(tracker_non_negative(persistent_gap_s), "tracking.persistent_gap_s", ">= 0");
  require(tracker_non_negative(persistent_memory_s), "tracking.persistent_memory_s", ">= 0");
  require(tracker_non_negative(mover_margin_m), "tracking.mover_margin_m", ">= 0");
  require(tracker_positive(max_range_m), "tracking.max_range_m", "> 0");
  require(tracker_positive(cluster_cell_m), "tracking.cluster_cell_m", "> 0");
  require(min_cluster_points >= 1, "tracking.min_cluster_points", ">= 1");
  require(tracker_positive(max_cluster_radius_m), "tracking.max_cluster_radius_m", "> 0");
  require(near_surface_quantile >= 0.0 && near_surface_quantile <= 1.0, "tracking.near_surface_quantile", "in [0, 1]");
  require(tracker_positive(point_noise_m), "tracking.point_noise_m", "> 0");
  require(tracker_non_negative(shape_noise_ratio), "tracking.shape_noise_ratio", ">= 0");
  require(tracker_non_negative(lateral_noise_ratio), "tracking.lateral_noise_ratio", ">= 0");
  parse_motion_model(motion_model);
  require(tracker_positive(accel_psd_m2ps3), "tracking.accel_psd_m2ps3", "> 0");
  require(tracker_positive(imm_turn_accel_psd_m2ps3), "tracking.imm_turn_accel_psd_m2ps3", "> 0");
  require(tracker_positive(turn_rate_psd_rad2ps3), "tracking.turn_rate_psd_rad2ps3", "> 0");
  require(tracker_positive(imm_switch_rate_hz), "tracking.imm_switch_rate_hz", "> 0");
  require(tracker_positive(initial_speed_std_mps), "tracking.initial_speed_std_mps", "> 0");
  require(tracker_positive(initial_turn_rate_std_radps), "tracking.initial_turn_rate_std_radps", "> 0");
  require(tracker_positive(gate_chi2), "tracking.gate_chi2", "> 0");
  require(confirm_hits >= 1, "tracking.confirm_hits", ">= 1");
  require(confirm_window >= confirm_hits && confirm_window <= 32, "tracking.confirm_window", "in [confirm_hits, 32]");
  require(tracker_non_negative(max_unseen_in_view_s), "tracking.max_unseen_in_view_s", ">= 0");
  require(tracker_non_negative(max_unseen_out_of_view_s) && max_unseen_out_of_view_s >= max_unseen_in_view_s,
          "tracking.max_unseen_out_of_view_s", ">= max_unseen_in_view_s");
  require(tracker_positive(max_position_std_m), "tracking.max_position_std_m", "> 0");
  require(tracker_non_negative(mover_speed_mps), "tracking.mover_speed_mps", ">= 0");
  require(tracker_positive(mover_window_s), "tracking.mover_window_s", "> 0");
  require(tracker_positive(mover_min_span_s) && mover_min_span_s <= mover_window_s, "tracking.mover_min_span_s",
          "in (0, mover_window_s]");
  require(tracker_positive(free_birth_min_span_s) && free_birth_min_span_s <= mover_window_s,
          "tracking.free_birth_min_span_s", "in (0, mover_window_s]");
  require(tracker_non_negative(free_birth_free_s), "tracking.free_birth_free_s", ">= 0");
  require(tracker_non_negative(free_birth_recent_s), "tracking.free_birth_recent_s", ">= 0");
  require(tracker_non_negative(mover_significance), "tracking.mover_significance", ">= 0");
  require(tracker_non_negative(mover_proof_m), "tracking.mover_proof_m", ">= 0");
  require(tracker_non_negative(mover_min_height_span_m), "tracking.mover_min_height_span_m", ">= 0");
  require(tracker_non_negative(mover_vacated_radius_m), "tracking.mover_vacated_radius_m", ">= 0");
  require(tracker_non_negative(radius_memory_s), "tracking.radius_memory_s", ">= 0");
  require(tracker_non_negative(horizon_s), "tracking.horizon_s", ">= 0");
  require(tracker_positive(prediction_step_s), "tracking.prediction_step_s", "> 0");
  require(horizon_s / prediction_step_s <= 1000.0, "tracking.prediction_step_s", ">= horizon_s / 1000");
}

}  // namespace bipednav::tracking
