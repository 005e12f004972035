#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bench/humanoid_drift.hpp"
#include "bench/kitti_odometry.hpp"
#include "bipednav/common/point_cloud.hpp"

// `bipednav bench localization`: LOAM per simulated VLP-16 sweep, GICP on the fast_gicp scan pair,
// LOAM and GICP odometry on KITTI HDL-64E sweeps, and the humanoid's drift per metre walked.
namespace bipednav::bench {

struct LocalizationBenchOptions {
  std::string scenario = "scenarios/three_rooms.yaml";  // the simulated sweeps' scenario (a YAML file)
  int sweeps = 100;                                     // simulated sweeps for LOAM
  // The scan pair's directory: 251370668.pcd, 251371071.pcd, relative.txt (empty:
  // tests/data/lidar/fast_gicp from the working directory).
  std::string data_dir;
  KittiOdometryOptions kitti;     // the KITTI rows
  HumanoidDriftOptions humanoid;  // the humanoid rows
};

// The LOAM rows (sweeps simulated along the scenario's widest route, the simulator's cost kept out of
// the timings), the GICP rows (three alignments of the scan pair against its relative.txt), the
// KITTI rows (bench_kitti_odometry) and the humanoid rows (bench_humanoid_drift), with their goals.
// Throws Error when the scan pair is not found.
nlohmann::json run_localization_bench(const LocalizationBenchOptions& options);

// A .pcd or .ply cloud without its non-finite points and its points at the sensor origin (no
// returns), voxel down-sampled when `voxel_m` > 0; throws FileError for another extension.
PointCloud load_cloud(const std::string& file, double voxel_m);

}  // namespace bipednav::bench
