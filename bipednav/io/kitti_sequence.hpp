#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"

namespace bipednav::io {

// A KITTI odometry sequence (Geiger, Lenz and Urtasun, CVPR 2012) in the benchmark's layout:
//   velodyne/NNNNNN.bin  one sweep per file: float32 x, y, z, reflectance per point, LiDAR frame
//   poses.txt            optional ground truth: T_cam0(0)_cam0(i), 12 numbers per line (3x4 row-major)
//   calib.txt            the line `Tr: ...` = T_cam0_velo (3x4 row-major); required with poses.txt
// The sweeps carry no per-point time or ring.

// One sweep file: intensities from the fourth value. Throws FileError naming the file when it
// cannot be read or its size is not a multiple of 16 bytes (it names the byte count).
PointCloud read_kitti_sweep(const std::filesystem::path& file);
PointCloud parse_kitti_sweep(std::string_view bytes, const std::string& name);

// `Tr:` of a calib.txt (other lines, e.g. P0..P3, are skipped). Throws FileError naming the file
// and line when Tr has not 12 numbers or its rotation is not orthonormal, or when there is none.
SE3 parse_kitti_calib_tr(std::string_view text, const std::string& name);
SE3 read_kitti_calib_tr(const std::filesystem::path& file);

// Camera poses to LiDAR poses: T_velo0_veloi = Tr^-1 * T_cam0_cami * Tr, Tr = T_cam0_velo.
std::vector<SE3> kitti_poses_in_lidar_frame(const std::vector<SE3>& T_cam0_cami, const SE3& Tr);

struct KittiSequence {
  std::filesystem::path dir;
  std::vector<std::filesystem::path> sweeps;  // velodyne/*.bin by name
  std::vector<SE3> T_lidar0_lidar;            // from poses.txt and calib.txt, or empty without poses.txt
};

// A directory holding velodyne/*.bin (or a velodyne directory itself). Throws FileError when
// there are no .bin files, when poses.txt has fewer poses than there are sweeps, or when
// poses.txt comes without calib.txt.
KittiSequence open_kitti_sequence(const std::filesystem::path& dir);
// True when `dir` holds velodyne/*.bin or *.bin sweeps.
bool is_kitti_sequence(const std::filesystem::path& dir);

}  // namespace bipednav::io
