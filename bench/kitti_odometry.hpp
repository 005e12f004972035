#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace bipednav::bench {

struct KittiOdometryOptions {
  std::string kitti_dir;  // a KITTI odometry folder (empty: tests/data/lidar/kitti00_f0-15)
};

// `bench localization`'s rows on the KITTI HDL-64E sweeps of `kitti_dir`: LOAM per sweep (one core)
// beside the scan-to-scan GICP baseline on the same sweeps, and both trajectories against the sweeps'
// direct registration and against poses.txt; a note when there are no sweeps.
nlohmann::json bench_kitti_odometry(const KittiOdometryOptions& options);

}  // namespace bipednav::bench
