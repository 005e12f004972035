// Odometry on recorded sweeps (`bipednav odometry PATH`): simulated VLP-16 sweeps without their
// ring and time fields, and the real KITTI HDL-64E sweeps read as KITTI and as a PCD folder.
#include "bipednav/runner/recorded_odometry.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

#include "bipednav/common/error.hpp"
#include "bipednav/io/kitti_sequence.hpp"
#include "bipednav/io/pcd.hpp"
#include "simulated_room.hpp"
#include "test_data.hpp"

namespace bipednav::runner {
namespace {

namespace fs = std::filesystem;

SweepSequence in_memory(std::vector<PointCloud> sweeps, std::vector<SE3> truth) {
  SweepSequence s;
  s.format = "memory";
  s.count = sweeps.size();
  s.truth = std::move(truth);
  s.read = [c = std::move(sweeps)](std::size_t i) { return c.at(i); };
  return s;
}

// 3 s of a VLP-16 moving at 1 m/s while turning at 0.5 rad/s: a sweep's start lies 0.1 m and
// 2.9 deg behind its end, so a sweep taken as a rigid snapshot is distorted.
struct SimulatedRun {
  std::vector<PointCloud> sweeps;
  std::vector<SE3> truth;
  SimulatedRun() {
    const auto pose_at = [](double t) { return make_se3(-2.0 + 1.0 * t, -1.0 + 0.3 * t * t, 1.2, 0, 0, 0.5 * t); };
    sweeps = test::simulated_vlp16_sweeps(test::lidar_room(), pose_at, 30, &truth);
  }
};

const SimulatedRun& simulated_run() {
  static const SimulatedRun run;
  return run;
}

double end_error(const RecordedOdometryResult& r) { return localization::end_point_error_m(r.truth, r.estimate); }

TEST(RecordedOdometry, SimulatedVlp16SweepsWithoutRingsAndTimesAreDeskewedFromTheirAzimuths) {
  const SimulatedRun& sim = simulated_run();
  std::vector<PointCloud> stripped = sim.sweeps;
  for (PointCloud& c : stripped) {
    c.rings.clear();
    c.time_offsets_s.clear();
  }
  RecordedOdometryOptions o;
  o.lidar = "vlp16";
  o.loam = loam_params_for_lidar("vlp16", {});
  const RecordedOdometryResult own = run_recorded_odometry(in_memory(sim.sweeps, sim.truth), o);
  const RecordedOdometryResult rebuilt = run_recorded_odometry(in_memory(stripped, sim.truth), o);
  o.deskew = false;
  const RecordedOdometryResult rigid = run_recorded_odometry(in_memory(stripped, sim.truth), o);
  EXPECT_EQ(own.ring_method, perception::RingMethod::from_cloud);
  EXPECT_EQ(rebuilt.ring_method, perception::RingMethod::beam_table);
  EXPECT_TRUE(rebuilt.times_from_azimuth);
  EXPECT_FALSE(rigid.times_from_azimuth);
  EXPECT_EQ(rebuilt.unhealthy, 0u);
  std::cout << "end-point error over " << localization::path_distances(sim.truth).back() << " m: simulator's fields "
            << end_error(own) << " m, rebuilt " << end_error(rebuilt) << " m, no times " << end_error(rigid) << " m\n";
  // The rebuilt rings are the simulator's and the times within 1 us of them: the same trajectory
  // within a millimetre (measured: 0.055 m end-point error over 4.1 m both); without times the
  // sweeps stay distorted (0.071 m).
  for (std::size_t i = 0; i < own.estimate.size(); ++i)
    EXPECT_LT((own.estimate[i].translation() - rebuilt.estimate[i].translation()).norm(), 1e-3) << i;
  EXPECT_LT(end_error(rebuilt), 0.08);
  EXPECT_GT(end_error(rigid), end_error(rebuilt) + 0.01);
  EXPECT_FALSE(rebuilt.map.empty());
}

TEST(RecordedOdometry, GicpBaselineFollowsTheSimulatedSweeps) {
  const SimulatedRun& sim = simulated_run();
  RecordedOdometryOptions o;
  o.method = "gicp";
  o.gicp_voxel_m = 0.3;
  const RecordedOdometryResult r = run_recorded_odometry(in_memory(sim.sweeps, sim.truth), o);
  ASSERT_EQ(r.estimate.size(), 30u);
  EXPECT_TRUE(r.estimate.front().isApprox(sim.truth.front()));
  EXPECT_LT(end_error(r), 0.3);  // no de-skew: each sweep is a distorted snapshot
}

TEST(RecordedOdometry, KittiHdl64SweepsFollowTheirOwnGeometryAndReadTheSameAsPcd) {
  BIPEDNAV_REQUIRE_DATA(first_sweep, "lidar/kitti00_f0-15/velodyne/000000.bin");
  const fs::path root = first_sweep.parent_path().parent_path();
  const io::SweepFiles files = io::open_sweep_files(root, io::SweepFormat::kitti);
  RecordedOdometryOptions o;
  o.lidar = "hdl64";
  o.loam = loam_params_for_lidar("hdl64", {});
  o.deskew = false;  // KITTI odometry's sweeps are motion-compensated
  const RecordedOdometryResult r = run_recorded_odometry(sweep_sequence_from_files(files), o);
  ASSERT_EQ(r.estimate.size(), 16u);
  EXPECT_EQ(r.ring_method, perception::RingMethod::scan_order);
  EXPECT_GE(r.ring_count, 64u);  // 64 lasers; a sweep may start mid-line
  EXPECT_LE(r.ring_count, 66u);
  EXPECT_EQ(r.unhealthy, 0u);

  // The sweeps' own trajectory (chained and direct GICP agree within 0.02 m over the 16 sweeps).
  const TrajectoryEvaluation own =
      evaluate_trajectory(direct_registration_trajectory(sweep_sequence_from_files(files)), r.estimate);
  EXPECT_LE(own.end_point_error_m, 0.10);
  EXPECT_LE(own.kitti_short.translation_percent, 1.0);
  // poses.txt: the path it gives (12.9 m) is 10 % longer than the sweeps' own (11.7 m, measured by
  // LOAM, by GICP chained and direct, and by the shift of the sweeps' occupancy grids), and it
  // turns 1.8 deg where the sweeps turn 3.0: it is not these sweeps' trajectory. Reported only.
  const TrajectoryEvaluation gt = evaluate_trajectory(r.truth, r.estimate);
  std::cout << "against the direct registration: end-point " << own.end_point_error_m << " m over " << own.distance_m
            << " m, KITTI " << own.kitti_short.translation_percent << " %; against poses.txt: " << gt.end_point_error_m
            << " m over " << gt.distance_m << " m, KITTI " << gt.kitti_short.translation_percent << " %\n";

  // The same sweeps written as a PCD folder give the same trajectory, bit for bit.
  const fs::path pcd = fs::temp_directory_path() / "bipednav_recorded_odometry_kitti_pcd";
  fs::remove_all(pcd);
  fs::create_directories(pcd);
  for (std::size_t i = 0; i < files.files.size(); ++i)
    io::write_pcd(pcd / files.files[i].filename().replace_extension(".pcd"), io::read_sweep(files, i),
                  io::PcdEncoding::binary);
  SweepSequence from_pcd = sweep_sequence_from_files(io::open_sweep_files(pcd, io::detect_sweep_format(pcd)));
  EXPECT_EQ(from_pcd.format, "pcd");
  from_pcd.truth = r.truth;
  const RecordedOdometryResult p = run_recorded_odometry(from_pcd, o);
  ASSERT_EQ(p.estimate.size(), r.estimate.size());
  for (std::size_t i = 0; i < r.estimate.size(); ++i) EXPECT_EQ(p.estimate[i].matrix(), r.estimate[i].matrix()) << i;
  fs::remove_all(pcd);
}

TEST(RecordedOdometry, RejectsAnEmptySequenceAndBadOptions) {
  RecordedOdometryOptions o;
  EXPECT_THROW(run_recorded_odometry(in_memory({}, {}), o), Error);
  o.method = "icp";
  EXPECT_THROW(run_recorded_odometry(in_memory({PointCloud{}}, {}), o), ParamError);
  o.method = "loam";
  o.lidar = "vlp32";
  EXPECT_THROW(run_recorded_odometry(in_memory({PointCloud{}}, {}), o), Error);
  o.lidar = "vlp16";
  EXPECT_THROW(run_recorded_odometry(in_memory({PointCloud{}, PointCloud{}}, {SE3::Identity()}), o), Error);
}

}  // namespace
}  // namespace bipednav::runner
