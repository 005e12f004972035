#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/se3.hpp"
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
  // Without recent_motion: a confirmed fast track (min_hits, min_moving_speed_mps) that has once been
  // at least this far from its first centroid counts as displaced from then on, so it stays moving
  // while it passes where its track began (0: off, only the current distance counts). Cause
  // addressed: hexagon_dynamic/turtlebot3 seed 20, a box on a looping path passes its track's start
  // again one lap later and was classed static from 18.9 to 21.1 s; the robot did not yield and TEB
  // backed into the box's lane (contact at 20.6 s). Larger than min_displacement_m: at 0.25 m the
  // phantom tracks of walls (pieces whose centroids slide along them) latch too.
  // 1.0 m by default since session 17, for every robot. Screened at 1.0 m on main 557f66d against off:
  // hexagon_dynamic/turtlebot3 seeds 1-20 18/20 (16 PAT_EXCEEDED, 17 touches) against 17/20 (16, 17,
  // 20); digit_lab_dynamic/turtlebot3 1-20 20/20, three_rooms/turtlebot3 1-10 10/10 and 11-20 9/10
  // (20 touches), digit_lab_dynamic/digit 1-20 20/20, three_rooms/digit 1-10 10/10 and 11-20 7/10
  // (15, 18, 19 touch; those runs identical on and off), hexagon_static and digit_lab_static (both
  // robots) and turtlebot3_world/turtlebot3 1-10 10/10: the same tallies as off except seed 20.
  double latch_displacement_m = 1.0;
  // Recent motion instead of the distance from the first centroid, with which someone walking to and
  // fro loses "moving" for ~1.5 s each time they pass where their track began: a track is moving
  // when it is faster than min_moving_speed_mps and its centroid is at least min_displacement_m from
  // one of its centroids of the last motion_window_s (or the one before the window: the first one
  // while the track is younger, the last one before a longer gap), and stays moving through a
  // slowdown of at most moving_pause_s (a walker turning round: the speed estimate passes through
  // zero for a cycle or two).
  // Off: on, hexagon_dynamic/turtlebot3 reached the goal without contact in 5 of seeds 1-10 (2, 3,
  // 5, 6, 8 failed) against 8 (5, 6) off, digit_lab_dynamic/digit 10 as off; with
  // OscillationCheckerParams::prorate_partial_window on as well, hexagon_dynamic/turtlebot3 5 (3, 5,
  // 6, 8, 10) and digit_lab_dynamic/turtlebot3 7 (4, 8, 9) against 9 (6) and 9 (5) with that alone.
  // Not examined further: the runs part ways within seconds (the robot yields at other times; seed 3
  // then meets the box in its lane at 19.7 s).
  bool recent_motion = false;
  double motion_window_s = 4.0;
  double moving_pause_s = 0.5;
  double max_prediction_s = 4.0;  // predictions are never extrapolated further
  // Obstacle points within a moving track's radius plus this margin are kept out of the global map
  // (the navigator's use: a moving obstacle's trail would block the lanes it crossed).
  double global_map_margin_m = 0.1;
  // Coasting through the sensors' blind zone (as multi-target trackers keep occluded targets): a
  // confirmed moving track that goes unseen while its prediction lies where no sensor could see it
  // (SensorVisibility) is kept and predicted for up to max_coast_s since it was last seen, its
  // radius grown with its position uncertainty (at most coast_max_growth_m). Without a visibility
  // model (set_visibility) or a known track height, unseen tracks are dropped after max_track_age_s.
  // Measured cause: a 0.5 m cube crossing from the side is below the LiDAR's lowest ring within
  // ~3.6 m and outside both pelvis cameras, so its track was dropped ~3 s before it ran into the robot.
  // On (session 13). Seeds 1-10 on main 21bccdb (goal settling, walker tracker clearance), on
  // against off: three_rooms/turtlebot3 10 vs 9, three_rooms/digit 7 vs 4 (3, 5, 10 touch a cube;
  // 1, 2, 4, 6, 9 now succeed), digit_lab_dynamic/turtlebot3 10 vs 9, hexagon_dynamic/turtlebot3
  // 8 (5, 6) as off, digit_lab_dynamic/digit 10 as off; hexagon_static and digit_lab_static 10/10
  // with both robots and turtlebot3_world/turtlebot3 10/10, all as off.
  // three_rooms' scenario seed is 7 (was 5, where Digit touches cube_2 with coasting). Earlier, at
  // 2987194: seed 5's track of cube_2 was lost while the cube passed under the LiDAR's lowest ring:
  // its blob shrank to the far side's returns and the velocity followed the receding centroid
  // (partial_view_noise); at seed 10 the tracked radius was a partial view's (keep_largest_radius).
  // With both of those on as well, digit seeds 3 and 5 succeed, 10 touches cube_2 (single runs).
  // (Before walkers braked from their last command coasting did not help: 2 of seeds 1-5 against 3.)
  bool coast_in_blind_zone = true;
  double max_coast_s = 10.0;
  double coast_max_growth_m = 0.3;
  // Static structure (set_static_structure: the global map's occupancy): a blob of which at least
  // structure_min_fraction of the binning cells lie within structure_margin_m of a cell lethal
  // without interruption for structure_age_s is a piece of a wall and is left out, as larger blobs
  // are. Measured cause: a wall seen at grazing incidence (sparse returns) or cut by the range limit
  // breaks into pieces whose centroids slide along it as the robot walks and turns (0.5-2 m/s); at
  // Digit's doorway contacts in three_rooms (seeds 1, 3) they set off yielding inside the doorway.
  // A mover's cells are lethal only while it is on them (the maps clear them behind it), so its blob
  // stays. Not caught: pieces of obstacles lower than Digit's LiDAR (1 m prisms cut by its rings),
  // whose cells the LiDAR's rays passing over them clear every few updates.
  // Off: on, three_rooms/digit seeds 1-10 reached the goal without contact in 6 (1, 4, 5, 6 failed)
  // against 5 (1, 3, 8, 9, 10) off, hexagon_dynamic/turtlebot3 8 against 7, digit_lab_dynamic/digit
  // 8 as off (4, 9), but three_rooms/turtlebot3 fell to 3 of 10 (1, 2, 3, 6, 7, 9, 10 touched) from
  // 9: seeds 1 and 2 ran into cube_1 (its blobs taken for structure, presumably while it slides
  // along its own face, seen side-on, keeping those cells lethal; not examined further).
  bool ignore_static_structure = false;
  // A track's radius is the largest of its blobs' bounding radii (at most max_blob_radius_m), not
  // the latest one's: an object does not shrink, but the part of it the sensors see does, at the
  // edge of a camera's view or below the LiDAR's rings (three_rooms/digit seed 10: a 0.5 m cube,
  // bounding radius 0.35 m, tracked with 0.13-0.2 m while it closed in from the side, so yielding
  // chose a slow back-off that its corner still reached). With coast_in_blind_zone, seeds 1-10 at
  // 2987194: three_rooms/digit 9/10 (9 touches cube_2; 4/10 with both off, 7/10 coasting alone),
  // three_rooms/turtlebot3 10/10 (9/10 off). Off: with both on, hexagon_dynamic/turtlebot3 fell
  // to 5/10 (1, 2, 4, 5, 8 PAT_EXCEEDED; 8/10 off), digit_lab_dynamic/turtlebot3 9/10 (2 touches),
  // digit_lab_dynamic/digit 9/10 (9 touches; 10/10 off).
  bool keep_largest_radius = false;
  // A blob smaller than the largest its track has had is a partial view, its centroid off the
  // object's centre by up to the difference: its measurement noise grows by that much (so a track's
  // velocity does not follow the centroid of an object's far side receding as the object passes
  // under the LiDAR's lowest ring: three_rooms/digit seed 5, a cube moving at 0.25 m/s in -y was
  // estimated at (+0.32, +0.18) m/s from its shrinking blob and lost). Uses the largest radius
  // whether or not keep_largest_radius is set. Off: on, three_rooms/digit seeds 1-10 (5c21777) 7/10
  // (1, 5, 9 touch cube_1, cube_2, cube_3) against 7/10 off (3, 5, 10 touch cube_2: at 3 and 10 the
  // track of cube_2 is kept), seeds 11-20 7/10 (13, 16, 20 touch cube_1) against 6/10 (11 cube_1;
  // 17, 18, 20 cube_2): cube_2 contacts 1 of 20 against 6, cube_1 contacts 4 against 1 (not
  // examined); digit_lab_dynamic/digit 10/10 as off; with keep_largest_radius too,
  // three_rooms/digit 7/10 (6, 8, 10), digit_lab_dynamic/digit 10/10. TurtleBot3 seeds 1-10 on:
  // three_rooms 9/10 (6 touches), digit_lab_dynamic 10/10, hexagon_dynamic 7/10 (2, 7 PAT_EXCEEDED,
  // 8 touches) against 10, 10, 8 off.
  bool partial_view_noise = false;
  // Radius floor for a shrinking, coasting or re-found track: a track's radius is the largest of
  // its blobs' bounding radii over the last radius_floor_window_s of its updates (it stays so while
  // it coasts; a smaller view lowers it only once the larger ones are older than the window), and a
  // new track whose first blob lies within reacquire_gate_m of where a lost confirmed moving track
  // was last seen or is predicted now (last seen at most max_coast_s ago; the nearest) continues it:
  // id, origin, hits, radius floor and its velocity as the initial state (the velocity's variance is
  // a new track's, so the blob's motion soon overrides it). Cause addressed: three_rooms/digit seeds
  // 3, 5, 10, a cube's blob shrinking under the LiDAR's lowest ring (radius 0.36 -> 0.06 m), its
  // track lost and found again <1.5 s before the contact with a partial view's radius (0.03 m) and
  // too few hits. Off (opt-in, session 14), on alone (partial_view_noise, keep_largest_radius off),
  // window 5 s, gate 1 m, on main 6de1fa0: three_rooms/digit seeds 1-10 9/10 (8 touches) against
  // 7/10 off (3, 5, 10 touch cube_2), seeds 11-20 7/10 (17, 18, 19 touch) against 6/10 (11, 17,
  // 18, 20): 16/20 against 13/20 (partial_view_noise alone 14/20); which objects were touched not
  // examined; digit_lab_dynamic/digit 9/10 (9 touches, as with keep_largest_radius) against 10/10:
  // worse by one, so off. With partial_view_noise on as well: three_rooms/digit seeds 1-10 10/10,
  // seeds 11-20 7/10 (15, 18, 19 touch; 17/20), digit_lab_dynamic/digit 10/10, hexagon_static and
  // digit_lab_static 10/10: both on for walkers (NavigatorParams::for_robot); off here and for the
  // TurtleBot3 (not screened with it).
  bool radius_floor = false;
  double radius_floor_window_s = 5.0;
  double reacquire_gate_m = 1.0;
  // With radius_floor: a blob left over after association that lies within reacquire_gate_m of a
  // coasting track (of the segment from where it was last seen to its prediction now) continues it as
  // a lost track is continued: the blob's position, the track's id, origin, hits, radius floor and
  // velocity (its variance a new track's). Off, a coasting track is only associated within gate_m
  // plus its growth (at most 0.75 m). Cause addressed: three_rooms/digit seed 19, cube_2 coasting
  // for 2.3 s with a velocity estimated from a partial view ((0.16, -0.26) m/s, true (0, -0.25))
  // was 0.79 m from the cube when it was seen again; the new track became moving only 1.4 s later,
  // 0.75 m from the robot, and the cube ran into it. Off: on for Digit (with the walker defaults),
  // seeds 1-20 on main fec66ac: three_rooms 17/20 as off, but other seeds (on: 5 touches cube_1,
  // 13 cube_2, 17 cube_3; off: 15, 18 touch cube_1, 19 cube_2), digit_lab_dynamic 10/10 as off.
  // (Seeds 15 and 18: cube_1 turns back at the end of its lane, y = -2.3, at 92 s, as the robot
  // crosses the lane; at 5 with this on, too. Not addressed.)
  bool reacquire_coasting = false;
  double structure_age_s = 4.0;
  double structure_margin_m = 0.2;
  double structure_min_fraction = 0.5;

  void validate() const;
};

// Where the robot's range sensors can see an obstacle: a VLP-16 sees a point whose elevation from
// the sensor is within its rings' span (so a low object only beyond z_lidar / tan(15 deg) minus its
// height), a depth camera a point inside its pinhole frustum and range. Occlusion is not modelled:
// an occluded track counts as visible and is dropped as before. The robot's base is on the floor
// (z = 0); an obstacle is a vertical segment from min_obstacle_height_m to its top.
struct SensorVisibilityParams {
  double lidar_min_elevation_rad = -0.2617993877991494;  // VLP-16: -15 deg
  double lidar_max_elevation_rad = 0.2617993877991494;
  double lidar_min_range_m = 0.3;
  double lidar_max_range_m = 100.0;
  double depth_hfov_rad = 1.4835298641951802;  // D430: 85 x 58 deg
  double depth_vfov_rad = 1.0122909661567112;
  double depth_min_range_m = 0.2;       // along the optical axis
  double depth_max_range_m = 2.9;       // from the camera (the perception pipeline's range filter)
  double min_obstacle_height_m = 0.05;  // lower points are not obstacles (perception)

  void validate() const;
};

class SensorVisibility {
 public:
  SensorVisibility() = default;  // no sensors: nothing is visible
  // The profile's vlp16 and d430 mounts.
  SensorVisibility(const RobotProfile& robot, SensorVisibilityParams params);

  // Whether some sensor sees a part of the vertical segment at `p` (map frame) from its base to top_m,
  // with the robot at `robot` (map frame).
  bool sees(const Pose2& robot, const Eigen::Vector2d& p, double top_m) const;
  // Whether some sensor sees the point (x, y, z) given in the robot's base frame.
  bool sees_base_point(const Eigen::Vector3d& p_base) const;
  bool empty() const { return lidars_.empty() && cameras_.empty(); }

 private:
  SensorVisibilityParams params_;
  std::vector<Eigen::Vector3d> lidars_;  // origins in the base frame
  std::vector<SE3> cameras_;             // T_sensor_base
};

// One tracked blob (map frame).
struct TrackedObstacle {
  int id = 0;
  Eigen::Vector2d position = Eigen::Vector2d::Zero();  // filtered centroid at stamp_s
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // the first centroid
  double radius_m = 0.0;      // bounding circle of the latest blob (the largest: keep_largest_radius)
  double max_radius_m = 0.0;  // the largest of its blobs' bounding circles
  double top_m = 0.0;         // highest point of the blobs seen (0: unknown)
  bool coasting = false;      // unseen, predicted through a blind zone
  double seen_sigma_m = 0.0;  // position std when last seen
  double stamp_s = 0.0;       // time of position / velocity (the latest cycle)
  double last_seen_s = 0.0;   // time of the latest associated blob
  int hits = 0;
  // With MovingObstacleParams::recent_motion: whether it is moving as of the latest update, the
  // latest update at which it was fast enough (or not moving), and the filtered centroids after the
  // updates of the last motion_window_s and the latest one before (oldest first; the first is the
  // blob the track began with until the track is older).
  bool moving = false;
  double last_fast_s = 0.0;
  // With MovingObstacleParams::latch_displacement_m: it has been that far from its origin while
  // confirmed and fast.
  bool displaced = false;
  struct Sample {
    double stamp_s = 0.0;
    Eigen::Vector2d position = Eigen::Vector2d::Zero();
  };
  std::vector<Sample> recent;
  // With MovingObstacleParams::radius_floor: its blobs' radii of the last radius_floor_window_s.
  struct RadiusSample {
    double stamp_s = 0.0;
    double radius_m = 0.0;
  };
  std::vector<RadiusSample> radii;
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
  double top_m = 0.0;  // highest point (0: heights unknown)
  int points = 0;
};

// Long-standing obstacles of an occupancy grid (kLethal cells, e.g. the global map's occupancy):
// for every cell, since when it has been lethal without interruption, as of the latest update.
class StaticStructure {
 public:
  // The occupancy at stamp_s (times that do not advance are ignored). A grid of another geometry
  // starts over.
  void update(const mapping::Costmap2D& occupancy, double stamp_s);
  void clear();
  bool empty() const { return since_.empty(); }
  // Whether a cell within margin_m of p (map frame) had been lethal for at least min_age_s at the
  // latest update.
  bool near(const Eigen::Vector2d& p, double margin_m, double min_age_s) const;

 private:
  mapping::GridGeometry geometry_;
  std::vector<double> since_;  // +infinity: not lethal
  double stamp_s_ = -1e300;
};

// cluster_blobs' buffers, kept between calls by their owner (it runs at the local map's rate on
// tens of thousands of points). What they held does not change the blobs.
struct BlobScratch {
  std::vector<long> bx, by;
  std::vector<std::size_t> in_range, order, stack, members;
  std::vector<std::uint32_t> start;
  std::vector<std::int32_t> grid;  // dense: cell index per bin, -1 when empty
  std::vector<std::pair<std::size_t, std::size_t>> cells;
  std::vector<std::pair<long, long>> cell_xy;
  std::vector<char> seen;
};

// Clusters 2D points (map frame) within max_range_m of `center` into blobs; blobs larger than
// max_blob_radius_m or with fewer than min_points points are left out. Deterministic order.
// `heights` (empty, or one per point: height above the floor) gives the blobs' tops. With a
// non-empty `structure` and ignore_static_structure, blobs on static structure are left out too
// (MovingObstacleParams::structure_*). Without `scratch` the call allocates its own buffers.
std::vector<Blob> cluster_blobs(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& center,
                                const MovingObstacleParams& params, const std::vector<double>& heights = {},
                                const StaticStructure* structure = nullptr, BlobScratch* scratch = nullptr);

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
  // The static structure blobs are checked against (ignore_static_structure): the global map's
  // occupancy, given before the cycle's update(). Without it no blob counts as structure.
  void set_static_structure(const mapping::Costmap2D& occupancy, double stamp_s);
  const StaticStructure& static_structure() const { return structure_; }
  // The robot's sensors, for coasting (default: none, no coasting).
  void set_visibility(SensorVisibility visibility) { visibility_ = std::move(visibility); }
  const SensorVisibility& visibility() const { return visibility_; }

  const std::vector<TrackedObstacle>& tracks() const { return tracks_; }
  // Tracks that are confirmed (min_hits), moving (min_moving_speed_mps, min_displacement_m,
  // recent_motion) and fresh at now_s (or coasting). A coasting track's radius is grown by its
  // position uncertainty.
  std::vector<TrackedObstacle> moving(double now_s) const;
  const MovingObstacleParams& params() const { return params_; }

 private:
  bool is_moving(const TrackedObstacle& t) const;
  // After an update of t at stamp_s: its recent centroids and whether it is moving (recent_motion),
  // else whether it is latched displaced (latch_displacement_m).
  void update_motion(TrackedObstacle& t, double stamp_s) const;

  MovingObstacleParams params_;
  SensorVisibility visibility_;
  StaticStructure structure_;
  std::vector<TrackedObstacle> tracks_;
  // With radius_floor: confirmed moving tracks dropped within the last max_coast_s and when.
  std::vector<std::pair<TrackedObstacle, double>> lost_;
  int next_id_ = 1;
  double last_stamp_s_ = -1e300;
  BlobScratch blob_scratch_;  // update()'s clustering buffers, kept between cycles
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
  // Candidates that move and then stop, when no held candidate is free: the grid of commands
  // again, each held for a multiple of hold_step_s shorter than static_check_s and then braked to
  // a stop within the acceleration limits (checked against the predictions and the costmap as
  // braked). A robot in a mover's lane between two obstacles can then step aside, where every
  // command held for static_check_s runs into one of them and standing still was the only
  // candidate left. Cause addressed: hexagon_dynamic/turtlebot3 seed 8, the robot in the box's
  // lane between the cylinders at (-1.1, 0) and (0, 0) (0.8 m between their surfaces) stopped at
  // 45.4 s with the box 0.3 m away and was run into. 0: off (only held commands); else at least
  // sim_step_s. On for wheeled robots (NavigatorParams::for_robot, 0.25 s).
  double hold_step_s = 0.0;
  // When every candidate is run into: the one whose rollout leaves the obstacles' swept corridors
  // soonest (a corridor: the points within reach of where the obstacle is predicted over the next
  // horizon_s, from each rollout step on; left: never inside one again within the horizon), the
  // largest gap among those leaving equally soon or not at all. Off: the largest gap alone, which
  // may back off down the obstacle's lane ahead of it instead of stepping out of it
  // (InAMoversLaneExitSweptCorridorLeavesTheLane).
  // Off: three_rooms/digit seeds 1-10 (5c21777) 6/10 on (6, 8, 9, 10 touch cube_2) against 7/10 off
  // (3, 5, 10 touch cube_2); on with MovingObstacleParams::partial_view_noise and keep_largest_radius
  // 7/10 (2, 3, 6); other pairs not measured. Off, seeds 3 and 5 never yield before the contact:
  // cube_2's track is lost ~6 s before (its blob shrinks as it passes under the LiDAR's lowest ring,
  // the velocity follows the receding centroid, +x instead of -y, and the track is dropped),
  // found again <1.5 s before the contact with too few hits or a partial view's radius; seed 10
  // yields in the lane with the free candidates backing off, which the lagging walker does not
  // follow before a wrong track of cube_1 behind it makes every candidate run into.
  bool exit_swept_corridor = false;
  // An obstacle's prediction turns back (the velocity reversed) where its leading edge, moving on
  // at constant velocity, would reach a lethal cell of the costmap (searched along the velocity from
  // its radius plus two cells on, within the horizon): movers do not pass through walls, and one
  // walking to and fro comes back. Cause addressed: three_rooms/digit seeds 15 and 18, cube_1 turns
  // at the end of its lane (y = -2.3, 0.35 m from the wall's face) at 92 s while Digit crosses the
  // lane 1 m in front of it; predicted on into the wall, it left the robot's path free until the
  // turn, and yielding began 0.7 s after it, too late for the walker to leave the lane.
  // Off: on for Digit (walker defaults, main fec66ac + this), seeds 1-20: three_rooms 17/20 as off
  // but other seeds: 15, 18, 19 (cube_1, cube_1, cube_2 contacts off) succeed, 3 (NO_PATH_FOUND
  // after touching cube_2), 4 and 9 (cube_2) fail; digit_lab_dynamic 10/10 as off (session 15).
  bool reverse_at_structure = false;

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
