#include "bipednav/io/kitti_sequence.hpp"

#include <algorithm>
#include <cstring>

#include "bipednav/common/error.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/io/sweep_folder.hpp"
#include "bipednav/io/trajectory_file.hpp"

namespace bipednav::io {

namespace fs = std::filesystem;

PointCloud parse_kitti_sweep(std::string_view bytes, const std::string& name) {
  constexpr std::size_t kStride = 4 * sizeof(float);
  if (bytes.size() % kStride != 0)
    throw FileError(name, "",
                    "expected float32 x, y, z, reflectance per point (a multiple of 16 bytes), got " +
                        std::to_string(bytes.size()) + " bytes");
  const std::size_t n = bytes.size() / kStride;
  PointCloud c;
  c.points.resize(n);
  c.intensities.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    float v[4];
    std::memcpy(v, bytes.data() + i * kStride, kStride);  // the files are little-endian, as this host
    c.points[i] = Eigen::Vector3f(v[0], v[1], v[2]);
    c.intensities[i] = v[3];
  }
  return c;
}

PointCloud read_kitti_sweep(const fs::path& file) {
  return parse_kitti_sweep(detail::read_file_bytes(file), file.string());
}

SE3 parse_kitti_calib_tr(std::string_view text, const std::string& name) {
  std::size_t line_no = 0;
  for (const std::string_view line : detail::text_lines(text)) {
    ++line_no;
    if (line.substr(0, 3) != "Tr:") continue;
    const std::vector<double> v = detail::parse_number_line(line.substr(3), name, line_no);
    if (v.size() != 12)
      throw FileError(name, "line " + std::to_string(line_no),
                      "Tr: expected 12 numbers (3x4 row-major), got " + std::to_string(v.size()));
    return detail::se3_from_kitti_row(v, name, line_no);
  }
  throw FileError(name, "", "no 'Tr:' line (the LiDAR-to-camera transform)");
}

SE3 read_kitti_calib_tr(const fs::path& file) {
  return parse_kitti_calib_tr(detail::read_file_bytes(file), file.string());
}

std::vector<SE3> kitti_poses_in_lidar_frame(const std::vector<SE3>& T_cam0_cami, const SE3& Tr) {
  std::vector<SE3> out;
  out.reserve(T_cam0_cami.size());
  const SE3 Tr_inv = Tr.inverse();
  for (const SE3& P : T_cam0_cami) out.push_back(Tr_inv * P * Tr);
  return out;
}

namespace {

fs::path velodyne_dir(const fs::path& dir) { return fs::is_directory(dir / "velodyne") ? dir / "velodyne" : dir; }

}  // namespace

bool is_kitti_sequence(const fs::path& dir) {
  return fs::is_directory(dir) && !list_sweep_files(velodyne_dir(dir), ".bin").empty();
}

KittiSequence open_kitti_sequence(const fs::path& dir) {
  KittiSequence s;
  s.dir = dir;
  const fs::path vdir = velodyne_dir(dir);
  s.sweeps = list_sweep_files(vdir, ".bin");
  if (s.sweeps.empty()) throw FileError(dir.string(), "", "no velodyne/*.bin sweeps (a KITTI odometry sequence)");
  const fs::path root = vdir == dir ? dir.parent_path() : dir;
  const fs::path poses = root / "poses.txt", calib = root / "calib.txt";
  if (!fs::exists(poses)) return s;
  if (!fs::exists(calib))
    throw FileError(calib.string(), "",
                    "missing: poses.txt is in the camera frame, calib.txt's Tr relates it to the LiDAR");
  const Trajectory cam = read_trajectory(poses);
  if (!cam.stamps_s.empty()) throw FileError(poses.string(), "", "expected KITTI poses (12 numbers per line), got TUM");
  if (cam.poses.size() < s.sweeps.size())
    throw FileError(
        poses.string(), "",
        "expected a pose per sweep (" + std::to_string(s.sweeps.size()) + "), got " + std::to_string(cam.poses.size()));
  std::vector<SE3> first(cam.poses.begin(), cam.poses.begin() + static_cast<std::ptrdiff_t>(s.sweeps.size()));
  s.T_lidar0_lidar = kitti_poses_in_lidar_frame(first, read_kitti_calib_tr(calib));
  return s;
}

}  // namespace bipednav::io
