#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/runner/recorded_odometry.hpp"

// No ROS headers here: `bipednav odometry` links this without ROS compile flags.
namespace bipednav::ros1 {

// The sensor_msgs/PointCloud2 messages of `topic` in a rosbag, in the bag's time order, each read
// when asked for (x, y, z and the optional intensity, time and ring fields; conversions.hpp).
// An empty topic takes the bag's only PointCloud2 topic. Throws FileError naming the bag when it
// cannot be opened, when the topic holds no PointCloud2 messages, or when an empty topic is
// ambiguous (the PointCloud2 topics are listed).
runner::SweepSequence open_bag_sweeps(const std::filesystem::path& bag, const std::string& topic);

// Writes each sweep as one PointCloud2 message on `topic`, stamped with its stamp_s (the sweep's
// 0.1 s x (index + 1) when that is 0). Throws FileError when the bag cannot be written.
void write_bag_sweeps(const std::filesystem::path& bag, const std::string& topic,
                      const std::vector<PointCloud>& sweeps);

}  // namespace bipednav::ros1
