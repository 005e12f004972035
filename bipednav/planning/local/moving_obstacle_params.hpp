#pragma once

namespace bipednav::planning::local {

// Tracking small obstacles between sensor cycles (in the spirit of costmap_converter's blob
// tracking): the obstacle points of one cycle are binned into a grid, 8-connected cells form
// blobs, small blobs are associated with the tracks by gated nearest neighbour, and each track's
// centroid runs through a constant-velocity Kalman filter (per axis).
// `enabled` is the one switch for tracking and for yielding to the tracked obstacles (local
// planners and the navigator's final command).
struct MovingObstacleParams {
  bool enabled = true;
  double cluster_cell_m = 0.10;       // binning grid; blobs are 8-connected sets of occupied bins
  int min_points = 3;                 // smaller blobs are noise
  double max_blob_radius_m = 0.45;    // larger blobs (walls, furniture) are static structure
  double max_range_m = 5.0;           // only points this close to the robot are clustered
  double gate_m = 0.45;               // association gate around a track's predicted position
  double max_track_age_s = 0.6;       // a track unseen this long is dropped
  double measurement_noise_m = 0.04;  // centroid noise (std)
  double accel_noise_mps2 = 1.0;      // process noise of the constant-velocity model (std)
  double max_speed_mps = 2.0;         // velocity estimates are clipped to this
  int min_hits = 4;                   // a track needs this many updates before it may be "moving"
  double min_moving_speed_mps = 0.1;  // slower tracks count as static (the costmap handles them)
  // ... and so do tracks whose centroid has not travelled this far from where it was first seen
  // (a static object's centroid wanders while the robot sees more or less of it).
  double min_displacement_m = 0.25;
  // ... and so do tracks whose origin another object holds: a blob of the cycle, not within the
  // track's largest radius of it (its own object), reaches within this distance of its first
  // centroid. A track passed from one post to the next, or a centroid jumping as the blobs of
  // neighbouring posts merge and part, has a static object where it began; a mover has left it
  // (tracking::MultiObjectTracker's test of the same name). Walls and other blobs larger than
  // max_blob_radius_m do not count: a mover may start beside one.
  double vacated_radius_m = 0.1;
  // A confirmed fast track (min_hits, min_moving_speed_mps) that has once been at least this far
  // from its first centroid counts as displaced from then on, so it stays moving while it passes
  // where its track began (0: off, only the current distance counts): a box on a looping path was
  // classed static one lap later and TEB backed into its lane. Larger than min_displacement_m: at
  // 0.25 m the phantom tracks of walls (pieces whose centroids slide along them) latch too. On for
  // every robot (evidence: docs/closed-loop-log.md, 'Parameter evidence',
  // MovingObstacleParams).
  double latch_displacement_m = 1.0;
  double max_prediction_s = 4.0;  // predictions are never extrapolated further
  // Obstacle points within a moving track's radius plus this margin are kept out of the global map
  // (the navigator's use: a moving obstacle's trail would block the lanes it crossed).
  double global_map_margin_m = 0.1;
  // Coasting through the sensors' blind zone (as multi-target trackers keep occluded targets): a
  // confirmed moving track that goes unseen while its prediction lies where no sensor could see it
  // (SensorVisibility) is kept and predicted for up to max_coast_s since it was last seen, its
  // radius grown with its position uncertainty (at most coast_max_growth_m). Without a visibility
  // model (set_visibility) or a known track height, unseen tracks are dropped after max_track_age_s.
  // Why: a 0.5 m cube crossing from the side is below the LiDAR's lowest ring within ~3.6 m and
  // outside both pelvis cameras, so its track was dropped ~3 s before it ran into the robot. On for
  // every robot (evidence in docs/closed-loop-log.md, as above).
  bool coast_in_blind_zone = true;
  double max_coast_s = 10.0;
  double coast_max_growth_m = 0.3;
  // A blob smaller than the largest its track has had is a partial view, its centroid off the
  // object's centre by up to the difference: its measurement noise grows by that much (so a track's
  // velocity does not follow the centroid of an object's far side receding as the object passes
  // under the LiDAR's lowest ring). Off here; on for walkers together with radius_floor
  // (config/digit.params.yaml; evidence in docs/closed-loop-log.md, as above).
  bool partial_view_noise = false;
  // Radius floor for a shrinking, coasting or re-found track: a track's radius is the largest of
  // its blobs' bounding radii over the last radius_floor_window_s of its updates (it stays so while
  // it coasts; a smaller view lowers it only once the larger ones are older than the window), and a
  // new track whose first blob lies within reacquire_gate_m of where a lost confirmed moving track
  // was last seen or is predicted now (last seen at most max_coast_s ago; the nearest) continues it:
  // id, origin, hits, radius floor and its velocity as the initial state (the velocity's variance is
  // a new track's, so the blob's motion soon overrides it). Why: a cube's blob shrinking under the
  // LiDAR's lowest ring lost its track, found again just before contact with a partial view's radius
  // and too few hits. Off here; on for Digit with partial_view_noise (config/digit.params.yaml);
  // the TurtleBot3 was not screened with it (evidence in docs/closed-loop-log.md, as above).
  bool radius_floor = false;
  double radius_floor_window_s = 5.0;
  double reacquire_gate_m = 1.0;
  // Recurrence (a map of the movers' ways, kept as their trails): movers walk the same ways again
  // (a person pacing or shuttling, people using one door, a box on a loop, a cube in its lane), so
  // a mover is predicted to do what a mover did the last time one passed where it is, going its
  // way. The tracker keeps the moving tracks' filtered positions of the last recurrence_history_s
  // (0: off, constant velocity only); the latest pass at least recurrence_min_lag_s old within
  // recurrence_match_m of the mover, in its direction (within 45 degrees), gives the prediction:
  // the way that trail went on from there, for up to max_prediction_s, then constant velocity. A
  // mover where none went before keeps the constant velocity. On for every robot (evidence:
  // docs/closed-loop-log.md, 'Recurrence prediction of the movers').
  double recurrence_history_s = 60.0;
  double recurrence_match_m = 0.3;
  double recurrence_min_lag_s = 2.0;

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("enabled", enabled);
    v("cluster_cell_m", cluster_cell_m);
    v("min_points", min_points);
    v("max_blob_radius_m", max_blob_radius_m);
    v("max_range_m", max_range_m);
    v("gate_m", gate_m);
    v("max_track_age_s", max_track_age_s);
    v("measurement_noise_m", measurement_noise_m);
    v("accel_noise_mps2", accel_noise_mps2);
    v("max_speed_mps", max_speed_mps);
    v("min_hits", min_hits);
    v("min_moving_speed_mps", min_moving_speed_mps);
    v("min_displacement_m", min_displacement_m);
    v("vacated_radius_m", vacated_radius_m);
    v("latch_displacement_m", latch_displacement_m);
    v("max_prediction_s", max_prediction_s);
    v("global_map_margin_m", global_map_margin_m);
    v("coast_in_blind_zone", coast_in_blind_zone);
    v("max_coast_s", max_coast_s);
    v("coast_max_growth_m", coast_max_growth_m);
    v("partial_view_noise", partial_view_noise);
    v("radius_floor", radius_floor);
    v("radius_floor_window_s", radius_floor_window_s);
    v("reacquire_gate_m", reacquire_gate_m);
    v("recurrence_history_s", recurrence_history_s);
    v("recurrence_match_m", recurrence_match_m);
    v("recurrence_min_lag_s", recurrence_min_lag_s);
  }
};

}  // namespace bipednav::planning::local
