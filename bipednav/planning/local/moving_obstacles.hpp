#pragma once

#include <Eigen/Core>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/planning/local/moving_obstacle_params.hpp"
#include "bipednav/planning/local/obstacle_blobs.hpp"
#include "bipednav/tracking/sensor_visibility.hpp"

namespace bipednav::planning::local {

// One tracked blob (map frame).
struct TrackedObstacle {
  int id = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // filtered centroid at stamp_s
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // the first centroid
  double radius_m = 0.0;      // bounding circle of the latest blob (radius_floor: of its recent ones)
  double max_radius_m = 0.0;  // the largest of its blobs' bounding circles
  double top_m = 0.0;         // highest point of the blobs seen (0: unknown)
  bool coasting = false;      // unseen, predicted through a blind zone
  double seen_sigma_m = 0.0;  // position std when last seen
  double stamp_s = 0.0;       // time of position / velocity (the latest cycle)
  double last_seen_s = 0.0;   // time of the latest associated blob
  int hits = 0;
  // With MovingObstacleParams::latch_displacement_m: it has been that far from its origin while
  // confirmed and fast.
  bool displaced = false;
  // Another object of the latest cycle stands where it was first seen
  // (MovingObstacleParams::vacated_radius_m).
  bool origin_occupied = false;
  // With MovingObstacleParams::radius_floor: its blobs' radii of the last radius_floor_window_s.
  struct RadiusSample {
    double stamp_s = 0.0;
    double radius_m = 0.0;
  };
  std::vector<RadiusSample> radii;
  // Kalman state covariances, per axis (position, velocity).
  Eigen::Matrix2d cov_x = Eigen::Matrix2d::Identity();
  Eigen::Matrix2d cov_y = Eigen::Matrix2d::Identity();
  // With MovingObstacleParams::recurrence_history_s: the way a mover went on from the latest
  // time one passed where this one was last seen, in the direction it goes (displacements from
  // that time; empty: none found). `recurrence_base_s` is when it was last seen, the displacements'
  // origin.
  struct PathSample {
    double t_s = 0.0;
    Eigen::Vector2d position = Eigen::Vector2d::Zero();
  };
  std::vector<PathSample> recurrence;
  double recurrence_base_s = 0.0;
  Eigen::Vector2d recurrence_base = Eigen::Vector2d::Zero();

  // The centroid at time t_s: along its recurrence where it has one that reaches t_s, then (and
  // without one) at constant velocity.
  Eigen::Vector2d predict(double t_s) const;
  // The centroid at time t_s at constant velocity (predict's fallback).
  Eigen::Vector2d predict_constant_velocity(double t_s) const { return position + velocity * (t_s - stamp_s); }
};

class MovingObstacleTracker {
 public:
  explicit MovingObstacleTracker(MovingObstacleParams params = {});

  // One sensor cycle: the obstacle points seen since the last update (map frame, any height),
  // the robot position (for the range limit) and the cycle's time. Non-finite points are skipped;
  // a time that does not advance is ignored.
  void update(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& robot, double stamp_s);
  // With the points' heights above the floor (one per point) and the robot's heading: tracks keep
  // their height and may coast through the blind zone of the visibility model.
  void update(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& heights, const Pose2& robot,
              double stamp_s);
  // Blobs instead of points (for tests and other sources); `robot` enables coasting.
  void update_blobs(const std::vector<Blob>& blobs, double stamp_s, const std::optional<Pose2>& robot = std::nullopt);
  void clear();
  // The robot's sensors, for coasting (default: none, no coasting).
  void set_visibility(tracking::SensorVisibility visibility) { visibility_ = std::move(visibility); }
  const tracking::SensorVisibility& visibility() const { return visibility_; }

  const std::vector<TrackedObstacle>& tracks() const { return tracks_; }
  // Tracks that are confirmed (min_hits), moving (min_moving_speed_mps, min_displacement_m,
  // latch_displacement_m) and fresh at now_s (or coasting). A coasting track's radius is grown by its
  // position uncertainty.
  std::vector<TrackedObstacle> moving(double now_s) const;
  const MovingObstacleParams& params() const { return params_; }

 private:
  bool is_moving(const TrackedObstacle& t) const;
  // After an update of t: whether it is latched displaced (latch_displacement_m).
  void latch_displaced(TrackedObstacle& t) const;
  // Before a cycle's association: origin_occupied of every track that may be moving, from the
  // cycle's blobs.
  void note_occupied_origins(const std::vector<Blob>& blobs);
  // update_blobs' steps, in order: the Kalman prediction of every track to stamp_s; the gated
  // nearest-neighbour association (marking the tracks and blobs used) and update_track for each pair;
  // keeping, coasting or dropping the unseen tracks; a track for every blob left (start_track, which
  // may continue a lost one instead).
  void predict_tracks(double stamp_s);
  void associate(const std::vector<Blob>& blobs, double stamp_s, std::vector<char>& track_used,
                 std::vector<char>& blob_used);
  void update_track(TrackedObstacle& t, const Blob& blob, double stamp_s) const;
  void keep_unseen(double stamp_s, const std::optional<Pose2>& robot, const std::vector<char>& track_used);
  void start_track(const Blob& blob, double stamp_s);
  // radius_floor: the new track t continues the nearest lost track within reacquire_gate_m, if any.
  void continue_lost(TrackedObstacle& t, const Blob& blob, double stamp_s);
  // recurrence_history_s: adds a moving t's position to its trail and finds its recurrence.
  void recur(TrackedObstacle& t, double stamp_s);

  MovingObstacleParams params_;
  tracking::SensorVisibility visibility_;
  std::vector<TrackedObstacle> tracks_;
  // With radius_floor: confirmed moving tracks dropped within the last max_coast_s and when.
  std::vector<std::pair<TrackedObstacle, double>> lost_;
  // recurrence_history_s: the moving tracks' filtered positions of that long, by track id.
  std::map<int, std::vector<TrackedObstacle::PathSample>> trails_;
  int next_id_ = 1;
  double last_stamp_s_ = -1e300;
  BlobScratch blob_scratch_;  // update()'s clustering buffers, kept between cycles
};

}  // namespace bipednav::planning::local
