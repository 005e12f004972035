#include "bipednav/io/kitti_sequence.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "bipednav/common/error.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/io/sweep_folder.hpp"

namespace bipednav::io {
namespace {

namespace fs = std::filesystem;

std::string sweep_bytes(const std::vector<std::array<float, 4>>& pts) {
  std::string s(pts.size() * 16, '\0');
  for (std::size_t i = 0; i < pts.size(); ++i) std::memcpy(s.data() + 16 * i, pts[i].data(), 16);
  return s;
}

void write_text(const fs::path& f, const std::string& s) { std::ofstream(f, std::ios::binary) << s; }

// KITTI's calibration: the camera looks along the LiDAR's x (camera z forward, x right, y down).
const char* kCalib =
    "P0: 1 0 0 0 0 1 0 0 0 0 1 0\n"
    "Tr: 0 -1 0 0.1 0 0 -1 -0.2 1 0 0 -0.3\n";

TEST(KittiSequence, ParsesASweepAndRejectsATruncatedOne) {
  const PointCloud c = parse_kitti_sweep(sweep_bytes({{1, 2, 3, 0.5f}, {-4, 5.5f, -6, 0}}), "a.bin");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c.points[1], Eigen::Vector3f(-4, 5.5f, -6));
  EXPECT_EQ(c.intensities, (std::vector<float>{0.5f, 0.0f}));
  try {
    parse_kitti_sweep(std::string(20, '\0'), "b.bin");
    ADD_FAILURE();
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("b.bin: expected float32 x, y, z, reflectance"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("got 20 bytes"), std::string::npos);
  }
}

TEST(KittiSequence, CalibrationAndCameraPosesBecomeLidarPoses) {
  const SE3 Tr = parse_kitti_calib_tr(kCalib, "calib.txt");
  EXPECT_TRUE(Tr.linear().isApprox((Eigen::Matrix3d() << 0, -1, 0, 0, 0, -1, 1, 0, 0).finished()));
  // The camera moves 2 m forward (its z) and turns 0.1 rad left (about its -y): the LiDAR moves
  // 2 m along its x (plus the lever arm of the turn) and turns 0.1 rad about its z.
  SE3 P = SE3::Identity();
  P.linear() = Eigen::AngleAxisd(0.1, -Eigen::Vector3d::UnitY()).toRotationMatrix();
  P.translation() = Eigen::Vector3d(0, 0, 2);
  const std::vector<SE3> lidar = kitti_poses_in_lidar_frame({SE3::Identity(), P}, Tr);
  EXPECT_TRUE(lidar[0].isApprox(SE3::Identity()));
  EXPECT_NEAR(pose2_from_se3(lidar[1]).theta, 0.1, 1e-12);
  const Eigen::Matrix3d R = Tr.linear();
  const Eigen::Vector3d t = Tr.translation();
  EXPECT_TRUE(lidar[1].translation().isApprox(R.transpose() * (P.linear() * t + P.translation() - t), 1e-12));
  // Without the lever arm (Tr's translation) the LiDAR moves exactly 2 m along its x.
  SE3 Tr0 = Tr;
  Tr0.translation().setZero();
  EXPECT_TRUE(kitti_poses_in_lidar_frame({P}, Tr0)[0].translation().isApprox(Eigen::Vector3d(2, 0, 0), 1e-12));
}

TEST(KittiSequence, CalibrationErrorsNameTheLine) {
  EXPECT_THROW(parse_kitti_calib_tr("P0: 1 0 0 0\n", "calib.txt"), FileError);
  try {
    parse_kitti_calib_tr("P0: 1\nTr: 1 0 0 0 0 1 0 0 0 0 1\n", "calib.txt");
    ADD_FAILURE();
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("calib.txt:line 2: Tr: expected 12 numbers"), std::string::npos);
  }
}

TEST(KittiSequence, OpensAFolderInNaturalOrderWithItsPoses) {
  const fs::path dir = fs::temp_directory_path() / "bipednav_kitti_sequence_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "velodyne");
  for (const char* name : {"000010.bin", "000002.bin", "000001.bin"})
    write_text(dir / "velodyne" / name, sweep_bytes({{1, 0, 0, 0}}));
  EXPECT_TRUE(is_kitti_sequence(dir));
  EXPECT_EQ(detect_sweep_format(dir), SweepFormat::kitti);
  KittiSequence s = open_kitti_sequence(dir);
  ASSERT_EQ(s.sweeps.size(), 3u);
  EXPECT_EQ(s.sweeps[2].filename(), "000010.bin");
  EXPECT_TRUE(s.T_lidar0_lidar.empty());  // no poses.txt
  write_text(dir / "poses.txt", "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 1\n");
  EXPECT_THROW(open_kitti_sequence(dir), FileError);  // poses without calib.txt
  write_text(dir / "calib.txt", kCalib);
  try {
    open_kitti_sequence(dir);
    ADD_FAILURE();
  } catch (const FileError& e) {  // two poses for three sweeps
    EXPECT_NE(std::string(e.what()).find("expected a pose per sweep (3), got 2"), std::string::npos);
  }
  write_text(dir / "poses.txt",
             "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 1\n1 0 0 0 0 1 0 0 0 0 1 2\n1 0 0 0 0 1 0 0 0 0 1 3\n");
  s = open_kitti_sequence(dir / "velodyne");  // the velodyne folder itself finds its parent's files
  ASSERT_EQ(s.T_lidar0_lidar.size(), 3u);
  EXPECT_TRUE(s.T_lidar0_lidar[2].translation().isApprox(Eigen::Vector3d(2, 0, 0), 1e-12));
  fs::remove_all(dir);
}

TEST(SweepFolder, DetectsPcdAndPlyFoldersAndNamesWhatIsMissing) {
  const fs::path dir = fs::temp_directory_path() / "bipednav_sweep_folder_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  EXPECT_THROW(detect_sweep_format(dir), FileError);
  EXPECT_THROW(detect_sweep_format(dir / "missing.bag"), FileError);
  PointCloud c;
  c.points = {{1, 2, 3}};
  for (const char* name : {"scan10.pcd", "scan9.pcd", "scan09b.pcd"}) write_pcd(dir / name, c);
  EXPECT_EQ(detect_sweep_format(dir), SweepFormat::pcd);
  const SweepFiles f = open_sweep_files(dir, SweepFormat::pcd);
  ASSERT_EQ(f.files.size(), 3u);
  EXPECT_EQ(f.files[0].filename(), "scan9.pcd");
  EXPECT_EQ(f.files[1].filename(), "scan09b.pcd");
  EXPECT_EQ(f.files[2].filename(), "scan10.pcd");
  EXPECT_EQ(read_sweep(f, 2).points, c.points);
  EXPECT_THROW(open_sweep_files(dir, SweepFormat::ply), FileError);
  EXPECT_THROW(sweep_format_from_string("las"), Error);
  write_text(dir / "run.bag", "");
  EXPECT_EQ(detect_sweep_format(dir / "run.bag"), SweepFormat::rosbag);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace bipednav::io
