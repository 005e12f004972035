// Sweeps through a rosbag of sensor_msgs/PointCloud2: written, read back, and the KITTI sweeps'
// odometry from a bag equal to the odometry from their folder.
#include "ros/bag_sweeps.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "bipednav/common/error.hpp"
#include "bipednav/io/sweep_folder.hpp"
#include "test_data.hpp"

namespace bipednav::ros1 {
namespace {

namespace fs = std::filesystem;

PointCloud small_sweep(float shift) {
  PointCloud c;
  c.points = {{1 + shift, 2, 3}, {-4, 5, 6}, {7, -8, 9}};
  c.intensities = {1, 2, 3};
  c.time_offsets_s = {0.0f, 0.05f, 0.09f};
  c.rings = {0, 7, 15};
  c.frame_id = "velodyne";
  return c;
}

TEST(BagSweeps, WritesAndReadsSweepsWithTheirFields) {
  const fs::path bag = fs::temp_directory_path() / "bipednav_bag_sweeps_test.bag";
  write_bag_sweeps(bag, "/points", {small_sweep(0), small_sweep(1)});
  const runner::SweepSequence s = open_bag_sweeps(bag, "");  // the only PointCloud2 topic
  ASSERT_EQ(s.count, 2u);
  EXPECT_EQ(s.format, "rosbag");
  const PointCloud c = s.read(1);
  EXPECT_EQ(c.points, small_sweep(1).points);
  EXPECT_EQ(c.time_offsets_s, small_sweep(1).time_offsets_s);
  EXPECT_EQ(c.rings, small_sweep(1).rings);
  EXPECT_NEAR(c.stamp_s, 0.2, 1e-9);  // stamp 0: 0.1 s x (index + 1)
  EXPECT_THROW(open_bag_sweeps(bag, "/other"), FileError);
  EXPECT_THROW(open_bag_sweeps(fs::temp_directory_path() / "no_such.bag", ""), FileError);
  fs::remove(bag);
}

TEST(BagSweeps, KittiSweepsFromABagGiveTheFoldersTrajectory) {
  BIPEDNAV_REQUIRE_DATA(first_sweep, "lidar/kitti00_f0-15/velodyne/000000.bin");
  const io::SweepFiles files = io::open_sweep_files(first_sweep.parent_path().parent_path(), io::SweepFormat::kitti);
  std::vector<PointCloud> sweeps;
  for (std::size_t i = 0; i < files.files.size(); ++i) sweeps.push_back(io::read_sweep(files, i));
  const fs::path bag = fs::temp_directory_path() / "bipednav_bag_sweeps_kitti.bag";
  write_bag_sweeps(bag, "/velodyne_points", sweeps);
  runner::RecordedOdometryOptions o;
  o.lidar = "hdl64";
  o.loam = runner::loam_params_for_lidar("hdl64", {});
  o.deskew = false;
  const runner::RecordedOdometryResult folder =
      runner::run_recorded_odometry(runner::sweep_sequence_from_files(files), o);
  runner::SweepSequence from_bag = open_bag_sweeps(bag, "/velodyne_points");
  from_bag.truth = folder.truth;
  const runner::RecordedOdometryResult r = runner::run_recorded_odometry(from_bag, o);
  ASSERT_EQ(r.estimate.size(), folder.estimate.size());
  for (std::size_t i = 0; i < r.estimate.size(); ++i)
    EXPECT_EQ(r.estimate[i].matrix(), folder.estimate[i].matrix()) << i;
  fs::remove(bag);
}

}  // namespace
}  // namespace bipednav::ros1
