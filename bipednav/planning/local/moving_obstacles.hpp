#pragma once

#include <Eigen/Core>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/planning/local/plan_utils.hpp"

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
  double max_prediction_s = 4.0;  // predictions are never extrapolated further
  // Obstacle points within a moving track's radius plus this margin are kept out of the global map
  // (the navigator's use: a moving obstacle's trail would block the lanes it crossed).
  double global_map_margin_m = 0.1;

  void validate() const;
};

// One tracked blob (map frame).
struct TrackedObstacle {
  int id = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // filtered centroid at stamp_s
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // the first centroid
  double radius_m = 0.0;                             // bounding circle of the latest blob
  double stamp_s = 0.0;                              // time of position / velocity (the latest cycle)
  double last_seen_s = 0.0;                          // time of the latest associated blob
  int hits = 0;
  // Kalman state covariances, per axis (position, velocity).
  Eigen::Matrix2d cov_x = Eigen::Matrix2d::Identity();
  Eigen::Matrix2d cov_y = Eigen::Matrix2d::Identity();

  // Constant-velocity prediction of the centroid at time t_s.
  Eigen::Vector2d predict(double t_s) const { return position + velocity * (t_s - stamp_s); }
};

// A blob of one cycle: centroid and bounding radius of its points.
struct Blob {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
  int points = 0;
};

// Clusters 2D points (map frame) within max_range_m of `center` into blobs; blobs larger than
// max_blob_radius_m or with fewer than min_points points are left out. Deterministic order.
std::vector<Blob> cluster_blobs(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& center,
                                const MovingObstacleParams& params);

class MovingObstacleTracker {
 public:
  explicit MovingObstacleTracker(MovingObstacleParams params = {});

  // One sensor cycle: the obstacle points seen since the last update (map frame, any height),
  // the robot position (for the range limit) and the cycle's time. Non-finite points are skipped;
  // a time that does not advance is ignored.
  void update(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& robot, double stamp_s);
  // Blobs instead of points (for tests and other sources).
  void update_blobs(const std::vector<Blob>& blobs, double stamp_s);
  void clear();

  const std::vector<TrackedObstacle>& tracks() const { return tracks_; }
  // Tracks that are confirmed (min_hits), fresh at now_s and faster than min_moving_speed_mps.
  std::vector<TrackedObstacle> moving(double now_s) const;
  const MovingObstacleParams& params() const { return params_; }

 private:
  MovingObstacleParams params_;
  std::vector<TrackedObstacle> tracks_;
  int next_id_ = 1;
  double last_stamp_s_ = -1e300;
};

// Yielding to moving obstacles: the command is checked against the constant-velocity predictions
// of the moving tracks over horizon_s; when the robot would come closer than its radius plus the
// blob's plus the margin, a safer command is chosen among slower, turning and backing candidates
// (collision-free against the costmap): the one closest to the planner's command that no moving
// obstacle runs into, else the one that keeps the largest gap to them.
// Yielding runs whenever the planner is given a tracker whose MovingObstacleParams::enabled is set
// (the one switch for tracking and yielding).
struct DynamicAvoidanceParams {
  double horizon_s = 3.0;
  double robot_radius_m = 0.25;
  double safety_margin_m = 0.15;
  // The reach grows this much per second of prediction: a constant-velocity prediction misses the
  // obstacle's turns (hexagon_dynamic's box turns a corner 0.3 m from a robot waiting for it).
  double prediction_growth_mps = 0.05;
  double sim_step_s = 0.1;
  double static_check_s = 1.5;  // candidate arcs are checked against the costmap this far ahead

  void validate() const;
};

// Time until the robot driving (v, w) from `pose` at now_s first comes within reach of a moving
// obstacle's prediction; +infinity when not within horizon_s.
double time_to_collision(const Pose2& pose, const Twist& cmd, const std::vector<TrackedObstacle>& moving, double now_s,
                         const DynamicAvoidanceParams& params);

struct YieldDecision {
  Twist cmd;
  Twist target;           // the chosen candidate before the acceleration limits
  bool modified = false;  // the command was replaced
  double ttc_s = 0.0;     // time to collision of the returned command (inf: none predicted)
};

// Keeps `cmd` when no collision with a moving obstacle is predicted, else returns the safest
// candidate (see DynamicAvoidanceParams). The result is within the velocity and acceleration
// limits from `current`.
YieldDecision yield_to_moving_obstacles(const Twist& cmd, const Pose2& pose, const Twist& current,
                                        const std::vector<TrackedObstacle>& moving, const mapping::Costmap2D& costmap,
                                        const CommandLimits& lim, double period_s, double now_s,
                                        const DynamicAvoidanceParams& params);

}  // namespace bipednav::planning::local
