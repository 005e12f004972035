#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/common/robot_profile.hpp"
#include "bipednav/common/sensor_frame.hpp"
#include "bipednav/common/twist.hpp"
#include "bipednav/perception/decimation.hpp"
#include "bipednav/perception/fusion.hpp"
#include "bipednav/perception/ground_segmentation.hpp"
#include "bipednav/perception/pass_through.hpp"
#include "bipednav/perception/plane.hpp"
#include "bipednav/perception/voxel_grid.hpp"

namespace bipednav::perception {

struct PerceptionParams {
  VoxelGridParams depth_voxel;  // 0.02 m (section 4.2.1)
  // Decimation of the depth images before the voxel grid (decimation.hpp; 1 = off). At 2 the
  // D430's pixel spacing (3.6 mrad at 424 px: 7 mm at 2 m, 10 mm at 2.9 m) becomes 14-21 mm; on
  // the Digit frame the 0.02 m voxels drop by a third (the far floor at a grazing angle), the
  // obstacles' 5 cm occupancy keeps 67 of 68 cells (tests/perception), for a quarter of the points.
  int depth_decimation = 2;
  int depth_image_width = 424;     // points per row of the organised depth clouds (the D430 at 424 x 240)
  double depth_max_range_m = 2.9;  // from each depth camera (section 4.2.2)
  double lidar_min_range_m = 0.0;  // e.g. to drop hits on the robot's own body
  double lidar_max_range_m = 100.0;
  double lidar_voxel_m = 0.0;  // 0 = the LiDAR sweep is not downsampled
  // Motion-compensate the LiDAR sweep (deskew.hpp) with the base's measured twist before it is placed
  // with the pose of the frame it completes in. Off: geometrically right (tests/sim/lidar_deskew_test:
  // a spinning TurtleBot3's sweep within 1 cm of the wall, up to 0.1-0.5 m off without), but the
  // closed loops, tuned on skewed sweeps, lose runs with it (docs/closed-loop-log.md, 'LiDAR
  // de-skewing for the maps').
  bool deskew_lidar = false;
  RansacParams ransac = default_ransac();
  Plane prior_ground = ground_plane_z0();  // fallback ground in the base frame (base_link on the floor)
  double max_ground_offset_m = 0.3;        // a fitted plane this far from the prior at the base origin is rejected
  std::size_t min_ground_inliers = 30;     // fewer inliers -> the prior is used
  double min_obstacle_height_m = 0.05;     // above the ground; lower points are neither ground nor obstacle
  double obstacle_height_margin_m = 0.0;   // obstacles up to robot height + this
  std::uint64_t seed = 1;                  // RANSAC sampling

  static RansacParams default_ransac() {
    RansacParams r;
    r.distance_threshold_m = 0.03;
    r.success_probability = 0.99;
    r.max_iterations = 200;
    r.use_normal_prior = true;  // the ground is within 15 deg of the base frame's z axis
    return r;
  }
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v.group("depth_voxel", depth_voxel);
    v("depth_decimation", depth_decimation);
    v("depth_image_width", depth_image_width);
    v("depth_max_range_m", depth_max_range_m);
    v("lidar_min_range_m", lidar_min_range_m);
    v("lidar_max_range_m", lidar_max_range_m);
    v("lidar_voxel_m", lidar_voxel_m);
    v("deskew_lidar", deskew_lidar);
    v.group("ransac", ransac);
    v("prior_ground", prior_ground);
    v("max_ground_offset_m", max_ground_offset_m);
    v("min_ground_inliers", min_ground_inliers);
    v("min_obstacle_height_m", min_obstacle_height_m);
    v("obstacle_height_margin_m", obstacle_height_margin_m);
    v("seed", seed);
  }
};

struct PerceptionTimings {
  double depth_ms = 0.0;           // voxel grid + range filter + transform of all depth clouds
  double lidar_ms = 0.0;           // range filter (+ voxel) + transform of the sweep
  double segmentation_ms = 0.0;    // RANSAC
  double classification_ms = 0.0;  // ground / obstacle split
  double total_ms = 0.0;
};

// The sensor data of one frame, by pointer into the caller's clouds (no copies).
struct PerceptionInput {
  double stamp_s = 0.0;
  const PointCloud* lidar = nullptr;
  Twist base_velocity;  // body twist at stamp_s (odometry), for de-skewing the sweep
  std::vector<const DepthCloud*> depth;
};

// All clouds are in the base frame (frame_id "base_link", stamp of the sensor frame).
struct PerceptionOutput {
  PointCloud obstacles;                       // min_obstacle_height_m <= height above ground <= robot height (+ margin)
  std::vector<std::uint8_t> obstacle_source;  // index into `sources`, per obstacle point
  PointCloud ground;                          // RANSAC inliers (eq. 4.3) of the ground plane
  std::vector<std::uint8_t> ground_source;
  Plane ground_plane = ground_plane_z0();  // [a, b, c, d], unit normal, c >= 0, base frame
  bool plane_from_ransac = false;          // false: the prior plane was used (see PerceptionParams)
  std::size_t ground_inliers = 0;
  std::vector<SensorSource> sources;       // origins for ray-trace clearing
  std::size_t depth_points_in = 0;         // finite depth points received
  std::size_t depth_points_decimated = 0;  // after decimation (= depth_points_in without it)
  std::size_t depth_points_voxel = 0;      // after the range filter and the voxel grid
  PerceptionTimings timings;
};

// Depth clouds: decimation (an organised cloud of depth_image_width columns; others pass whole) ->
// range filter (<= depth_max_range_m from the camera) -> voxel grid -> base frame.
// LiDAR sweep: range filter (-> voxel grid) -> base frame. The fused cloud is segmented by RANSAC
// with a normal prior; a plane that is missing, has too few inliers or lies more than
// max_ground_offset_m from the prior (Digit's LiDAR sees the floor only beyond ~5.5 m, so a frame
// without depth clouds may show no floor at all) is replaced by the prior plane z = 0 and
// plane_from_ransac is false. Points below the ground (reflections) are dropped.
class PerceptionPipeline {
 public:
  explicit PerceptionPipeline(PerceptionParams params);

  // Throws Error when a depth cloud names a camera the robot profile does not mount, or a sweep
  // arrives without a "vlp16" mount.
  PerceptionOutput process(const SensorFrame& frame, const RobotProfile& robot);
  // The same into `out`, whose buffers are reused (its contents are replaced).
  void process(const PerceptionInput& in, const RobotProfile& robot, PerceptionOutput& out);

  const PerceptionParams& params() const { return params_; }

 private:
  void add_depth(FusedCloud& fused, const DepthCloud& depth, const RobotProfile& robot, PerceptionOutput& out);
  void add_lidar(FusedCloud& fused, const PointCloud& sweep, const PerceptionInput& in, const RobotProfile& robot);
  void choose_plane(const PlaneFit& fit, PerceptionOutput& out) const;
  void classify(const FusedCloud& fused, double robot_height_m, PerceptionOutput& out) const;

  PerceptionParams params_;
  Rng rng_;
  VoxelGrid depth_voxel_;  // stages and buffers kept between frames (no per-frame allocation)
  PointCloud voxels_, decimated_, lidar_kept_, lidar_deskewed_;
  FusedCloud fused_;
  RansacScratch ransac_scratch_;
};

}  // namespace bipednav::perception
