#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/tracking/detection.hpp"
#include "bipednav/tracking/detections.hpp"
#include "bipednav/tracking/motion_test.hpp"
#include "bipednav/tracking/persistent_cells.hpp"
#include "bipednav/tracking/sensor_visibility.hpp"
#include "bipednav/tracking/static_structure.hpp"
#include "bipednav/tracking/track_filter.hpp"
#include "bipednav/tracking/tracker_params.hpp"

namespace bipednav::tracking {

// How far apart a track's positions have been: their range along eight directions 22.5 degrees
// apart. The largest range is the positions' diameter to within 2 % (cos 11.25 deg).
class Spread {
 public:
  void add(const Eigen::Vector2d& p);
  double diameter() const;  // 0 before the first position

 private:
  std::array<double, 8> lo_{}, hi_{};
  bool empty_ = true;
};

// A track's life cycle: tentative until confirm_hits of its first confirm_window updates hit;
// then confirmed while seen, coasting while unseen (deleted tracks are removed).
enum class TrackStatus { kTentative, kConfirmed, kCoasting };

// Which test of the mover classification (TrackerParams: movers) decided a confirmed track's
// latest update.
enum class MotionTest {
  kProven,          // its positions have spanned mover_proof_m: a mover
  kMoving,          // every test passed: a mover
  kFlat,            // no vertical surface shown (mover_min_height_span_m)
  kShortWindow,     // its detections span less than mover_min_span_s (free_birth_min_span_s)
  kStill,           // the fitted line runs too slowly or not significantly
  kOriginOccupied,  // points are still where it was (mover_vacated_radius_m)
};
const char* motion_test_name(MotionTest m);  // "proven", "moving", "flat", "short_window", "still", "origin_occupied"

struct Track {
  int id = 0;
  TrackStatus status = TrackStatus::kTentative;
  TrackFilter filter;
  double radius_m = 0.0;        // the detections' radius, decaying from their largest over radius_memory_s
  double top_m = 0.0;           // highest point seen
  double height_span_m = -1.0;  // the largest of its detections' height spans (-1: unknown)
  double born_s = 0.0, last_seen_s = 0.0, stamp_s = 0.0;  // stamp_s: time of the filter's estimate
  double confirmed_s = -1.0;                              // when it was confirmed (-1: not yet)
  double unseen_in_view_s = 0.0;                          // time unseen while predicted in view
  int updates = 0, hits = 0;                              // cycles since born, and those with a detection
  std::uint32_t hit_history = 0;                          // bit k: a hit k cycles ago
  bool mover = false;                                     // moving (TrackerParams: movers), or a proven mover
  MotionTest motion_test = MotionTest::kShortWindow;      // of its latest update while confirmed
  bool born_in_free = false;               // born where the static map saw free space (TrackerParams: movers)
  bool proven = false;                     // its positions spanned mover_proof_m: a mover for good
  Spread spread = {};                      // of its filtered positions
  std::vector<TimedPosition> recent = {};  // its detections of the last mover_window_s

  bool confirmed() const { return status != TrackStatus::kTentative; }
  Eigen::Vector2d position() const { return filter.state().head<2>(); }
  Eigen::Vector2d velocity() const { return filter.state().tail<2>(); }
  Eigen::Matrix2d position_covariance() const { return filter.covariance().topLeftCorner<2, 2>(); }
};

// A track's predicted position at t_s and its covariance.
struct PredictedState {
  double t_s = 0.0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
};

// A confirmed mover over the planning horizon: its states from its estimate's time every
// prediction_step_s up to horizon_s.
struct TrackPrediction {
  int id = 0;
  double radius_m = 0.0;
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  std::vector<PredictedState> states;
};

// The standard deviation along a position covariance's major axis: the square root of the larger
// eigenvalue of the symmetric 2 x 2 matrix (its upper off-diagonal entry is used), 0 when that is
// negative, NaN for a NaN matrix.
double major_sigma(const Eigen::Matrix2d& cov);

// The multi-object tracker: detections in (obstacle points the static map does not explain,
// clustered), tracks and predictions out. Each cycle predicts every track to the cycle's time,
// associates the detections by Mahalanobis gate and global nearest neighbour (associate), gives
// movers their gate missed the nearest detection left within reach (TrackerParams: life cycle),
// updates the associated tracks' filters, runs the life cycle (TrackerParams: M of N confirmation; an
// unseen confirmed track coasts, shorter while its prediction is in some sensor's view) and
// starts a tentative track on every detection left. Confirmed tracks that move are movers.
class MultiObjectTracker {
 public:
  // `visibility`: where the robot's sensors see (default none: every track counts as in view).
  explicit MultiObjectTracker(TrackerParams params = {}, SensorVisibility visibility = {});

  // The static map as of stamp_s: an occupancy grid (kLethal cells are obstacles), e.g. the
  // global costmap's occupancy; its cells lethal for static_age_s explain the points on them.
  void set_static_map(const mapping::Costmap2D& occupancy, double stamp_s);
  // One sensor cycle: the points in range add to the persistent cells (but those on confirmed
  // movers), those neither map explains are clustered into detections (detect_objects), then
  // update_detections.
  void update(const DetectionInput& in);
  // One cycle from given detections (map frame) at stamp_s with the robot at T_map_base (for the
  // visibility model). A time that does not advance, or a non-finite one, changes nothing;
  // non-finite detections are ignored.
  void update_detections(const std::vector<Detection>& detections, double stamp_s, const Pose2& T_map_base);
  void clear();

  const std::vector<Track>& tracks() const { return tracks_; }              // tentative ones included
  const std::vector<Detection>& detections() const { return detections_; }  // of the latest cycle
  const PersistentCells& persistent_cells() const { return persistent_; }
  // The confirmed movers (coasting included) over the horizon.
  std::vector<TrackPrediction> predictions() const;
  const TrackerParams& params() const { return params_; }

 private:
  // Assigns detections no track took (match: per track, its detection or -1) to the movers
  // without one that reach them (TrackerParams: life cycle), nearest first by the Hungarian
  // method, and restarts those movers' filters at their detections.
  void reacquire_movers(std::vector<int>& match, double stamp_s);
  void update_track(Track& t, const Detection& d, double stamp_s) const;
  // Sets t.mover, t.motion_test and t.proven after an update (TrackerParams: movers).
  void classify_motion(Track& t) const;
  // The tests of a track not yet proven, in order: the first that fails, or kMoving.
  MotionTest motion_evidence(const Track& t) const;
  // Whether the surface where t was seen first in its mover window holds fewer than
  // min_cluster_points of this cycle's points (always, without them: update_detections).
  bool vacated(const Track& t) const;
  // After a cycle without a detection: false when the track is to be deleted.
  bool keep_unseen(Track& t, double dt_s, const Pose2& robot) const;
  bool in_view(const Track& t, const Pose2& robot) const;
  void start_track(const Detection& d, double stamp_s);

  TrackerParams params_;
  SensorVisibility visibility_;
  StaticStructure static_;
  PersistentCells persistent_;
  std::vector<Track> tracks_;
  std::vector<Detection> detections_;
  const std::vector<Eigen::Vector3d>* cycle_points_ = nullptr;  // this cycle's points in range, during update()
  int next_id_ = 1;
  double last_stamp_s_ = -1e300;
};

}  // namespace bipednav::tracking
