#include "bipednav/io/trajectory_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "bipednav/common/error.hpp"

namespace bipednav::io {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_trajectory(text, "poses.txt");
  } catch (const FileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no FileError for:\n" << text;
  return "";
}

std::vector<SE3> some_poses() {
  return {SE3::Identity(), make_se3(1.5, -2.25, 0.125, 0.1, -0.2, 2.9), make_se3(-3, 4, 5, -3.0, 0.4, -1.2)};
}

TEST(TrajectoryFile, TumAndKittiFilesRoundTrip) {
  const auto dir = std::filesystem::temp_directory_path() / "bipednav_trajectory_file_test";
  std::filesystem::create_directories(dir);
  const std::vector<SE3> poses = some_poses();
  write_tum_trajectory(dir / "t.txt", {0.0, 0.1, 1e9 + 0.25}, poses);
  write_kitti_trajectory(dir / "k.txt", poses);
  const Trajectory tum = read_trajectory(dir / "t.txt"), kitti = read_trajectory(dir / "k.txt");
  ASSERT_EQ(tum.poses.size(), 3u);
  ASSERT_EQ(kitti.poses.size(), 3u);
  EXPECT_TRUE(kitti.stamps_s.empty());
  EXPECT_NEAR(tum.stamps_s[2], 1e9 + 0.25, 1e-6);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_TRUE(tum.poses[i].isApprox(poses[i], 1e-7)) << i;
    EXPECT_TRUE(kitti.poses[i].isApprox(poses[i], 1e-7)) << i;
  }
}

TEST(TrajectoryFile, ReadsCommentsBlankLinesAndAPlusSign) {
  const Trajectory t = parse_trajectory("# t x y z qx qy qz qw\n\n1 +2 3 4 0 0 0 1\r\n", "p.txt");
  ASSERT_EQ(t.poses.size(), 1u);
  EXPECT_EQ(t.poses[0].translation(), Eigen::Vector3d(2, 3, 4));
}

TEST(TrajectoryFile, MalformedLinesNameTheFileAndLine) {
  EXPECT_NE(error_of("1 0 0 0 0 0 0 1\n1 0 0\n").find("poses.txt:line 2: expected 8 values"), std::string::npos);
  EXPECT_NE(error_of("1 2 3\n").find("poses.txt:line 1: expected 8 values (TUM"), std::string::npos);
  EXPECT_NE(error_of("1 0 0 x 0 0 0 1\n").find("line 1: value 4: expected a finite number, got 'x'"),
            std::string::npos);
  EXPECT_NE(error_of("1 0 0 nan 0 0 0 1\n").find("value 4"), std::string::npos);
  EXPECT_NE(error_of("1 0 0 0 0 0 0 2\n").find("expected a unit norm"), std::string::npos);
  EXPECT_NE(error_of("1 0 0 0 0 2 0 0 0 0 1 0\n").find("not orthonormal"), std::string::npos);
  EXPECT_NE(error_of("# nothing\n").find("no poses"), std::string::npos);
  EXPECT_THROW(read_trajectory("/nonexistent/poses.txt"), FileError);
  EXPECT_THROW(write_tum_trajectory("/tmp/x.txt", {0.0}, some_poses()), Error);
}

}  // namespace
}  // namespace bipednav::io
