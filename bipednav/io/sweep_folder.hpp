#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"

namespace bipednav::io {

// Recorded LiDAR sweeps, one file per sweep: a KITTI odometry sequence (kitti_sequence.hpp) or a
// folder of PCD or PLY files; a rosbag of sensor_msgs/PointCloud2 is a single file (read in the ROS
// build).
enum class SweepFormat { kitti, pcd, ply, rosbag };
std::string to_string(SweepFormat f);
// "kitti" / "pcd" / "ply" / "rosbag"; throws Error naming the accepted values otherwise.
SweepFormat sweep_format_from_string(const std::string& s);

// The regular files of `dir` whose extension is `ext` (e.g. ".pcd", case-insensitive), in natural
// order of their names: runs of digits compare as numbers, so 2.pcd comes before 10.pcd and
// 000002.bin before 000010.bin.
std::vector<std::filesystem::path> list_sweep_files(const std::filesystem::path& dir, const std::string& ext);

// The format of `path` from its content: a .bag file is a rosbag; a directory holding
// velodyne/*.bin or *.bin is KITTI, else *.pcd is PCD, else *.ply is PLY. Throws FileError naming
// the path when it is none of these.
SweepFormat detect_sweep_format(const std::filesystem::path& path);

struct SweepFiles {
  SweepFormat format = SweepFormat::pcd;
  std::vector<std::filesystem::path> files;  // one sweep each, in order
  std::vector<SE3> T_lidar0_lidar;           // the KITTI sequence's ground truth, else empty
};

// The sweep files of a KITTI, PCD or PLY folder (throws Error for rosbag: not a folder of files,
// and FileError when the folder holds no file of the format).
SweepFiles open_sweep_files(const std::filesystem::path& path, SweepFormat format);
// Sweep i of the folder with the fields its file carries (FileError on malformed files).
PointCloud read_sweep(const SweepFiles& files, std::size_t i);

}  // namespace bipednav::io
