#pragma once

#include <string>

namespace bipednav::tracking {

// The motion model of a track's filter (TrackerParams::motion_model).
enum class MotionModel {
  kConstantVelocity,  // "cv": a Kalman filter on (x, y, vx, vy), white acceleration
  kImmCvCt,           // "imm": an IMM of that and a coordinated turn (x, y, vx, vy, omega) EKF
};
MotionModel parse_motion_model(const std::string& name);  // "cv" | "imm"

// Every parameter of the multi-object tracker (detections, clustering, filters, association, life
// cycle, predictions). SI units; a track's noise figures are standard deviations unless named psd.
struct TrackerParams {
  // --- Detections (detections.hpp): the obstacle points the static map does not explain.
  // A point within static_margin_m of a cell that has been lethal without interruption for
  // static_age_s (StaticStructure over the given occupancy grid) is the map's. A mover's cells are
  // lethal only while it stands on them: a 0.5 m person walking at 0.3 m/s covers a 0.1 m cell for
  // 2 s, so 4 s keeps walkers and drops walls a few seconds after they are first seen.
  double static_margin_m = 0.15;
  double static_age_s = 4.0;
  // A cell's lethal spell survives gaps up to this long (the map's ray clearing empties wall cells
  // now and then; StaticStructure). Not much longer: a person pacing or walking a loop comes back
  // to the same cells every few seconds, and with 5 s its cells became static structure and the
  // person untracked (docs/closed-loop-log.md, "Tracking module").
  double static_gap_s = 1.0;
  // Besides, the points' own persistent cells (PersistentCells, cluster_cell_m): hit without a
  // break longer than persistent_gap_s for persistent_span_s, kept until unhit for
  // persistent_memory_s. Points on a proven mover (mover_proof_m; within its radius plus
  // mover_margin_m of its prediction) add no evidence and are explained by neither map, so a
  // person who stops stays seen.
  double persistent_span_s = 3.0;
  double persistent_gap_s = 1.0;
  double persistent_memory_s = 30.0;
  double mover_margin_m = 0.15;
  double max_range_m = 8.0;  // points farther from the robot are not clustered (and not in view)

  // --- Clustering (clustering.hpp): Euclidean clustering on a grid.
  double cluster_cell_m = 0.10;       // points in 8-connected occupied cells form one cluster
  int min_cluster_points = 4;         // fewer points are noise
  double max_cluster_radius_m = 0.6;  // larger clusters are structure (walls, furniture), not tracked
  // Measurement model (cluster_measurement.hpp): the centre of a cluster seen from one side is
  // its nearest surface plus its half width along the line of sight; its covariance is the point
  // noise plus shape_noise_ratio times the half width along that line (the unseen depth), and
  // lateral_noise_ratio times it across.
  // The near surface's range: this quantile of the ranges of the points in the middle quarter
  // (low, since a sensor looking down also sees an object's top behind its near face).
  double near_surface_quantile = 0.25;
  double point_noise_m = 0.03;  // std of a point (LiDAR 0.02 m; depth cameras 0.003 z^2)
  double shape_noise_ratio = 0.25;
  double lateral_noise_ratio = 0.10;

  // --- Filter (kalman_cv.hpp, imm_cv_ct.hpp).
  std::string motion_model = "cv";
  // Continuous white-noise acceleration, power spectral density per axis (Bar-Shalom et al. 2001,
  // sec. 6.2.2): a walker's speed and heading changes.
  double accel_psd_m2ps3 = 0.05;
  double turn_rate_psd_rad2ps3 = 0.1;     // imm: the coordinated turn's turn-rate noise
  double imm_turn_accel_psd_m2ps3 = 0.5;  // imm: the coordinated turn's white acceleration
  double imm_switch_rate_hz = 0.5;        // imm: expected model switches per second
  double initial_speed_std_mps = 1.0;     // a new track's velocity prior (zero mean)
  double initial_turn_rate_std_radps = 0.5;

  // --- Association (association.hpp): Mahalanobis gate, then global nearest neighbour.
  double gate_chi2 = 11.83;  // chi-square, 2 dof: 99.73 % of true detections fall inside

  // --- Life cycle (tracker.hpp).
  int confirm_hits = 3;    // tentative -> confirmed after this many hits ...
  int confirm_window = 5;  // ... within its first this many updates (M of N)
  // A mover that its gate misses takes the nearest detection left over (after every track's gated
  // one) within the distance its speed covers since it was last seen, plus sqrt(gate_chi2) of the
  // position sigmas: a person who turns on the spot, whom the constant-velocity prediction
  // overshoots. Its filter starts again there (zero velocity, initial_speed_std_mps), keeping
  // its id; a proven mover stays one.
  // A confirmed track unseen coasts on its prediction; it is deleted once it has been unseen
  // while its prediction was in some sensor's view (SensorVisibility, within max_range_m) for
  // max_unseen_in_view_s, or unseen for max_unseen_out_of_view_s in all (a mover; any other
  // track max_unseen_in_view_s), or once its position std exceeds max_position_std_m.
  double max_unseen_in_view_s = 0.5;
  double max_unseen_out_of_view_s = 6.0;
  double max_position_std_m = 1.5;
  // A track's radius: its detections' largest, decaying towards smaller ones over this time (a
  // partial view, at the edge of a camera's view or under the LiDAR's lowest ring, is smaller).
  double radius_memory_s = 2.0;

  // --- Movers (tracker.hpp): a confirmed track is a mover while the line fitted to its
  // detections of the last mover_window_s (regression_velocity), spanning mover_min_span_s at
  // least, runs at mover_speed_mps or faster, with that speed at least mover_significance
  // standard errors; and for good once its positions have spanned mover_proof_m (Spread: a person
  // who stops stays one, and so does one pacing to and fro, wherever it was first seen). A static
  // object's measured centre jitters as the robot sees more or less of it. The rest are obstacles
  // the maps do not hold yet (clutter, a wall in its first seconds): tracked, not movers, deleted
  // once unseen for max_unseen_in_view_s wherever they are.
  double mover_speed_mps = 0.15;
  double mover_window_s = 2.0;
  double mover_min_span_s = 1.2;
  // ... or free_birth_min_span_s for a track born where the static map saw free space: its cell
  // free without a break for free_birth_free_s, until at most free_birth_recent_s before the
  // birth. An object that appears where there was nothing has moved there; clutter seen for the
  // first time lies in cells the map has not seen free.
  double free_birth_min_span_s = 0.6;
  double free_birth_free_s = 3.0;
  double free_birth_recent_s = 0.5;
  double mover_significance = 5.0;
  double mover_proof_m = 1.0;
  // ... and a mover has shown a vertical surface: detections spanning this much height (where
  // heights are known). The top of a box lower than a LiDAR, swept by one ring as the robot
  // walks, slides like a mover but lies flat.
  double mover_min_height_span_m = 0.1;
  // ... and has left where it was: fewer than min_cluster_points of the cycle's points lie within
  // mover_vacated_radius_m of the surface it showed at the start of its mover window. A wall
  // revealed bit by bit behind a post, whose visible piece slides as the robot walks, stays.
  double mover_vacated_radius_m = 0.1;

  // --- Predictions (tracker.hpp): 0 .. horizon_s every prediction_step_s.
  double horizon_s = 4.0;
  double prediction_step_s = 0.1;

  void validate() const;
  MotionModel model() const { return parse_motion_model(motion_model); }

  // Every field by name, in declaration order: v(key, field) (`bench tracking --variant`).
  template <class V>
  void visit_fields(V& v) {
    v("static_margin_m", static_margin_m);
    v("static_age_s", static_age_s);
    v("static_gap_s", static_gap_s);
    v("persistent_span_s", persistent_span_s);
    v("persistent_gap_s", persistent_gap_s);
    v("persistent_memory_s", persistent_memory_s);
    v("mover_margin_m", mover_margin_m);
    v("max_range_m", max_range_m);
    v("cluster_cell_m", cluster_cell_m);
    v("min_cluster_points", min_cluster_points);
    v("max_cluster_radius_m", max_cluster_radius_m);
    v("near_surface_quantile", near_surface_quantile);
    v("point_noise_m", point_noise_m);
    v("shape_noise_ratio", shape_noise_ratio);
    v("lateral_noise_ratio", lateral_noise_ratio);
    v("motion_model", motion_model);
    v("accel_psd_m2ps3", accel_psd_m2ps3);
    v("turn_rate_psd_rad2ps3", turn_rate_psd_rad2ps3);
    v("imm_turn_accel_psd_m2ps3", imm_turn_accel_psd_m2ps3);
    v("imm_switch_rate_hz", imm_switch_rate_hz);
    v("initial_speed_std_mps", initial_speed_std_mps);
    v("initial_turn_rate_std_radps", initial_turn_rate_std_radps);
    v("gate_chi2", gate_chi2);
    v("confirm_hits", confirm_hits);
    v("confirm_window", confirm_window);
    v("max_unseen_in_view_s", max_unseen_in_view_s);
    v("max_unseen_out_of_view_s", max_unseen_out_of_view_s);
    v("max_position_std_m", max_position_std_m);
    v("radius_memory_s", radius_memory_s);
    v("mover_speed_mps", mover_speed_mps);
    v("mover_window_s", mover_window_s);
    v("mover_min_span_s", mover_min_span_s);
    v("free_birth_min_span_s", free_birth_min_span_s);
    v("free_birth_free_s", free_birth_free_s);
    v("free_birth_recent_s", free_birth_recent_s);
    v("mover_significance", mover_significance);
    v("mover_proof_m", mover_proof_m);
    v("mover_min_height_span_m", mover_min_height_span_m);
    v("mover_vacated_radius_m", mover_vacated_radius_m);
    v("horizon_s", horizon_s);
    v("prediction_step_s", prediction_step_s);
  }
};

}  // namespace bipednav::tracking
