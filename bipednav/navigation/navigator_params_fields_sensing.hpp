#pragma once

// The field lists (navigator_params_yaml.cpp) of the sensing and mapping parameters of NavigatorParams:
// perception, localization (LOAM), the two costmaps, the sensor gate and the moving-obstacle tracker.
#include "bipednav/navigation/navigator.hpp"
#include "bipednav/planning/local/moving_obstacle_params.hpp"

namespace bipednav::navigation::param_fields {

// Fields that two structs share under the same names, listed once.

// The inflation and obstacle-layer fields of both costmaps (inflation(), obstacle_layer()).
template <class V, class Costmap>
void visit_layer_fields(V& v, Costmap& p) {
  v("inscribed_radius_m", p.inscribed_radius_m);
  v("inflation_radius_m", p.inflation_radius_m);
  v("cost_scaling_factor", p.cost_scaling_factor);
  v("obstacle_max_range_m", p.obstacle_max_range_m);
  v("raytrace_max_range_m", p.raytrace_max_range_m);
  v("height_aware_clearing", p.height_aware_clearing);
}

template <class V>
void visit_fields(V& v, perception::VoxelGridParams& p) {
  v("leaf_size_m", p.leaf_size_m);
}

template <class V>
void visit_fields(V& v, perception::RansacParams& p) {
  v("distance_threshold_m", p.distance_threshold_m);
  v("success_probability", p.success_probability);
  v("max_iterations", p.max_iterations);
  v("use_normal_prior", p.use_normal_prior);
  v("max_normal_angle_rad", p.max_normal_angle_rad);
  v("refit", p.refit);
  v("inlier_std", p.inlier_std);
  v("max_points", p.max_points);
}

template <class V>
void visit_fields(V& v, perception::PerceptionParams& p) {
  v.group("depth_voxel", p.depth_voxel);
  v("depth_decimation", p.depth_decimation);
  v("depth_image_width", p.depth_image_width);
  v("depth_max_range_m", p.depth_max_range_m);
  v("lidar_min_range_m", p.lidar_min_range_m);
  v("lidar_max_range_m", p.lidar_max_range_m);
  v("lidar_voxel_m", p.lidar_voxel_m);
  v("deskew_lidar", p.deskew_lidar);
  v.group("ransac", p.ransac);
  v("prior_ground", p.prior_ground);
  v("max_ground_offset_m", p.max_ground_offset_m);
  v("min_ground_inliers", p.min_ground_inliers);
  v("min_obstacle_height_m", p.min_obstacle_height_m);
  v("obstacle_height_margin_m", p.obstacle_height_margin_m);
  v("seed", p.seed);
}

template <class V>
void visit_fields(V& v, localization::FeatureParams& p) {
  v("neighbours_per_side", p.neighbours_per_side);
  v("sub_regions", p.sub_regions);
  v("max_edges_per_region", p.max_edges_per_region);
  v("max_planars_per_region", p.max_planars_per_region);
  v("map_feature_factor", p.map_feature_factor);
  v("edge_threshold", p.edge_threshold);
  v("planar_threshold", p.planar_threshold);
  v("min_range_m", p.min_range_m);
  v("max_range_m", p.max_range_m);
  v("occlusion_ratio", p.occlusion_ratio);
  v("parallel_beam_ratio", p.parallel_beam_ratio);
  v("max_neighbour_gap_ratio", p.max_neighbour_gap_ratio);
  v("rings", p.rings);
  v("min_elevation_rad", p.min_elevation_rad);
  v("max_elevation_rad", p.max_elevation_rad);
}

template <class V>
void visit_fields(V& v, localization::AssociationParams& p) {
  v("neighbours", p.neighbours);
  v("max_correspondence_m", p.max_correspondence_m);
  v("max_plane_deviation_m", p.max_plane_deviation_m);
  v("min_line_ratio", p.min_line_ratio);
  v("edge_weight", p.edge_weight);
}

template <class V>
void visit_fields(V& v, localization::LmParams& p) {
  v("max_iterations", p.max_iterations);
  v("bisquare_c_m", p.bisquare_c_m);
  v("initial_lambda", p.initial_lambda);
  v("degenerate_min_eigenvalue", p.degenerate_min_eigenvalue);
  v("converged_translation_m", p.converged_translation_m);
  v("converged_rotation_rad", p.converged_rotation_rad);
}

template <class V>
void visit_fields(V& v, localization::OdometryParams& p) {
  v("scan_period_s", p.scan_period_s);
  v.group("association", p.association);
  v("correspondence_rounds", p.correspondence_rounds);
  v("relaxation", p.relaxation);
  v("round_converged_translation_m", p.round_converged_translation_m);
  v("round_converged_rotation_rad", p.round_converged_rotation_rad);
  v("min_constraints", p.min_constraints);
  v.group("lm", p.lm);
}

template <class V>
void visit_fields(V& v, localization::MappingParams& p) {
  v("rate_hz", p.rate_hz);
  v("edge_leaf_m", p.edge_leaf_m);
  v("planar_leaf_m", p.planar_leaf_m);
  v("map_radius_m", p.map_radius_m);
  v.group("association", p.association);
  v("correspondence_rounds", p.correspondence_rounds);
  v("round_converged_translation_m", p.round_converged_translation_m);
  v("round_converged_rotation_rad", p.round_converged_rotation_rad);
  v("min_constraints", p.min_constraints);
  v("gravity_weight", p.gravity_weight);
  v.group("lm", p.lm);
}

template <class V>
void visit_fields(V& v, localization::LoamParams& p) {
  v.group("features", p.features);
  v.group("odometry", p.odometry);
  v.group("mapping", p.mapping);
  v("min_features", p.min_features);
  v("planar_constant_velocity", p.planar_constant_velocity);
  v("reference_from_prior_change", p.reference_from_prior_change);
  v("max_prior_change_m", p.max_prior_change_m);
  v("max_prior_change_rad", p.max_prior_change_rad);
  v("max_prior_error_change_rad", p.max_prior_error_change_rad);
  v("planar_motion", p.planar_motion);
}

template <class V>
void visit_fields(V& v, LocalizerParams& p) {
  v("method", p.method);
  v.group("loam", p.loam);
  v("sweep_duration_s", p.sweep_duration_s);
  v("max_correction_jump_m", p.max_correction_jump_m);
  v("max_correction_jump_rad", p.max_correction_jump_rad);
  v("unhealthy_after_bad_sweeps", p.unhealthy_after_bad_sweeps);
  v("odometry_timeout_s", p.odometry_timeout_s);
  v("max_odometry_speed_mps", p.max_odometry_speed_mps);
  v("max_odometry_rate_radps", p.max_odometry_rate_radps);
  v("odometry_drift_ratio", p.odometry_drift_ratio);
  v("scan_position_sigma_m", p.scan_position_sigma_m);
}

template <class V>
void visit_fields(V& v, mapping::LocalCostmapParams& p) {
  v("size_m", p.size_m);
  v("resolution_m", p.resolution_m);
  visit_layer_fields(v, p);
  v("mark_decay_s", p.mark_decay_s);
  v("rate_hz", p.rate_hz);
}

template <class V>
void visit_fields(V& v, mapping::GlobalCostmapParams& p) {
  v("resolution_m", p.resolution_m);
  v("default_size_m", p.default_size_m);
  visit_layer_fields(v, p);
  v("lidar_clearing", p.lidar_clearing);
  v("merge_local", p.merge_local);
  v("mark_decay_s", p.mark_decay_s);
  v("unknown_cost_mode", p.unknown_cost_mode);
  v("rate_hz", p.rate_hz);
}

template <class V>
void visit_fields(V& v, SensorGateParams& p) {
  v("max_age_s", p.max_age_s);
  v("min_valid_ratio", p.min_valid_ratio);
  v("sensor_timeout_s", p.sensor_timeout_s);
}

template <class V>
void visit_fields(V& v, planning::local::MovingObstacleParams& p) {
  v("enabled", p.enabled);
  v("cluster_cell_m", p.cluster_cell_m);
  v("min_points", p.min_points);
  v("max_blob_radius_m", p.max_blob_radius_m);
  v("max_range_m", p.max_range_m);
  v("gate_m", p.gate_m);
  v("max_track_age_s", p.max_track_age_s);
  v("measurement_noise_m", p.measurement_noise_m);
  v("accel_noise_mps2", p.accel_noise_mps2);
  v("max_speed_mps", p.max_speed_mps);
  v("min_hits", p.min_hits);
  v("min_moving_speed_mps", p.min_moving_speed_mps);
  v("min_displacement_m", p.min_displacement_m);
  v("latch_displacement_m", p.latch_displacement_m);
  v("max_prediction_s", p.max_prediction_s);
  v("global_map_margin_m", p.global_map_margin_m);
  v("coast_in_blind_zone", p.coast_in_blind_zone);
  v("max_coast_s", p.max_coast_s);
  v("coast_max_growth_m", p.coast_max_growth_m);
  v("partial_view_noise", p.partial_view_noise);
  v("radius_floor", p.radius_floor);
  v("radius_floor_window_s", p.radius_floor_window_s);
  v("reacquire_gate_m", p.reacquire_gate_m);
}

}  // namespace bipednav::navigation::param_fields
