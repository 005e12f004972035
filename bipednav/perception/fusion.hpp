#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/perception/pass_through.hpp"

namespace bipednav::perception {

// A sensor that contributed points: costmaps ray-trace free space from `origin_base` to each of
// its points (and up to max_range_m for clearing).
struct SensorSource {
  std::string name;                                       // mount name: "lidar", "depth_front", ...
  Eigen::Vector3d origin_base = Eigen::Vector3d::Zero();  // sensor origin in the base frame
  double max_range_m = 0.0;
};

// Points of several sensors in the base frame; source[i] indexes `sources` for point i.
struct FusedCloud {
  PointCloud cloud;  // xyz only (per-sensor time offsets and rings are not carried across sensors)
  std::vector<std::uint8_t> source;
  std::vector<SensorSource> sources;

  std::size_t size() const { return cloud.size(); }
};

// Transforms `in` (in the sensor frame) by T_base_sensor and appends it to `out` with a new source
// entry; non-finite points, and those failing `crop` (in the sensor frame) when given, are skipped.
// Returns the index of the source. Throws Error beyond 255 sources.
std::size_t append_sensor_cloud(FusedCloud& out, const PointCloud& in, const SE3& T_base_sensor,
                                const std::string& name, double max_range_m, const PassThroughTest* crop = nullptr);

}  // namespace bipednav::perception
