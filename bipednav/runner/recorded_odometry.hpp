#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/io/sweep_folder.hpp"
#include "bipednav/localization/gicp_odometry.hpp"
#include "bipednav/localization/loam.hpp"
#include "bipednav/localization/trajectory_metrics.hpp"
#include "bipednav/perception/scan_rings.hpp"

namespace bipednav::runner {

// Recorded sweeps in order (`bipednav odometry PATH`): a count, a reader, and reference poses
// T_world_lidar, one per sweep, when the recording has them.
struct SweepSequence {
  std::string format;  // "kitti", "pcd", "ply" or "rosbag"
  std::size_t count = 0;
  std::function<PointCloud(std::size_t)> read;
  std::vector<SE3> truth;  // empty, or one per sweep
};
SweepSequence sweep_sequence_from_files(io::SweepFiles files);

// LOAM's parameters for a LiDAR model: LoamParams' defaults overlaid with `params_file` (the
// navigation parameters layout, its localization.loam; see navigator_params_yaml.hpp), or, when
// that is empty, with config/lidar/<lidar>.yaml if it exists (per-sensor tuning as data), and the
// scan period from the model's rate. Returns the file used in `used_file` (empty: none).
localization::LoamParams loam_params_for_lidar(const std::string& lidar, const std::filesystem::path& params_file,
                                               std::filesystem::path* used_file = nullptr);

struct RecordedOdometryOptions {
  std::string lidar = "vlp16";  // perception::lidar_model name: beam table, rate, rotation
  std::string method = "loam";  // "loam", or "gicp" (scan-to-scan GICP, the baseline)
  localization::LoamParams loam;
  localization::GicpOdometryParams gicp;
  double gicp_voxel_m = 0.5;  // GICP's input down-sampling
  // Give sweeps without per-point times the times of their azimuths (perception::times_from_azimuth),
  // so that LOAM de-skews them. Off for recordings already de-skewed (KITTI odometry's sweeps).
  bool deskew = true;
  double map_voxel_m = 0.2;    // the accumulated map's leaf
  std::size_t max_sweeps = 0;  // 0: all
  bool progress = false;       // a progress bar on stderr
  void validate() const;
};

struct RecordedOdometryResult {
  std::vector<double> stamps_s;       // each sweep's stamp, else index / rate
  std::vector<SE3> estimate;          // T_world_lidar per sweep: world = the truth's frame (the first
                                      // estimate is the first reference pose), else the first sweep's
  std::vector<SE3> truth;             // the sequence's reference poses for the sweeps run (or empty)
  std::vector<double> method_ms;      // per sweep: LOAM odometry + mapping, or GICP with its down-sampling
  std::vector<double> mapping_ms;     // per sweep: LOAM's mapping step (0 on sweeps without one)
  std::vector<double> method_cpu_ms;  // per sweep: the method's thread CPU time (one core; no preemption)
  std::vector<double> preprocess_ms;  // per sweep: ring and time reconstruction
  std::size_t points = 0;             // over all sweeps read
  std::size_t unhealthy = 0, degenerate = 0;
  perception::RingMethod ring_method = perception::RingMethod::from_cloud;  // of the last sweep
  std::size_t ring_count = 0;
  bool times_from_azimuth = false;  // some sweep got its times from its azimuths
  PointCloud map;                   // the sweeps (de-skewed) in the world frame, voxel-downsampled
};

// Runs the odometry over the sequence. Throws Error on an empty sequence or bad options,
// FileError from the readers.
RecordedOdometryResult run_recorded_odometry(const SweepSequence& seq, const RecordedOdometryOptions& o);

// The sweeps' own trajectory, for recordings whose reference poses are missing or in doubt: each
// sweep registered directly onto the first (GICP on `voxel_m` voxels without the points closer
// than `min_range_m`, from the previous result extrapolated), not chained, so that no odometry
// error accumulates in it; valid while every sweep overlaps the first. T_first_lidar per sweep.
std::vector<SE3> direct_registration_trajectory(const SweepSequence& seq, double voxel_m = 0.2,
                                                double min_range_m = 3.0);

// The estimate against the truth (equal lengths): ATE after SE(3) alignment, RPE over one frame
// and over `rpe_distance_m` of path, KITTI's relative errors over its 100..800 m segments and over
// every whole-metre length the path allows (from every frame), and the end-point error.
struct TrajectoryEvaluation {
  double distance_m = 0.0;
  double end_point_error_m = 0.0;
  localization::AbsoluteError ate;
  localization::RelativeError rpe_frame;
  double rpe_distance_m = 0.0;
  localization::RelativeError rpe_distance;
  localization::KittiError kitti;        // the benchmark's segments (none on short sequences)
  localization::KittiError kitti_short;  // 1, 2, ... m segments from every frame
  std::size_t kitti_short_step_frames = 1;
};
TrajectoryEvaluation evaluate_trajectory(const std::vector<SE3>& truth, const std::vector<SE3>& estimate,
                                         double rpe_distance_m = 5.0);

}  // namespace bipednav::runner
