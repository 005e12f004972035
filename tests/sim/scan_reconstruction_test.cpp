// A simulated VLP-16 sweep with its ring and time fields stripped gets them back from the beam
// table (exactly) and from the azimuths (within 1 us); the HDL-64E methods on synthetic sweeps.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bipednav/common/error.hpp"
#include "bipednav/perception/lidar_model.hpp"
#include "bipednav/perception/scan_rings.hpp"
#include "bipednav/perception/scan_times.hpp"
#include "simulated_room.hpp"

using namespace bipednav;

namespace {

// One sweep of the simulator's VLP-16 while the sensor moves and turns.
PointCloud simulated_sweep() {
  const auto pose_at = [](double t) { return make_se3(1.0 * t, 0.3 * t, 1.2, 0.02, -0.01, 0.8 * t); };
  return test::simulated_vlp16_sweeps(test::lidar_room(), pose_at, 1).front();
}

}  // namespace

TEST(ScanReconstruction, SimulatedVlp16RingsComeBackExactlyAndTimesWithinAMicrosecond) {
  const PointCloud truth = simulated_sweep();
  ASSERT_GT(truth.size(), 25000u);  // 16 x 1800 beams, all returning
  ASSERT_TRUE(truth.has_ring() && truth.has_time());
  PointCloud stripped = truth;
  stripped.rings.clear();
  stripped.time_offsets_s.clear();

  const perception::LidarModel vlp16 = perception::lidar_model("vlp16");
  const perception::RingReconstruction r = perception::reconstruct_rings(stripped, vlp16);
  EXPECT_EQ(r.method, perception::RingMethod::beam_table);
  EXPECT_EQ(r.ring_count, 16u);
  EXPECT_EQ(r.rings, truth.rings);

  // The simulator spins clockwise from azimuth 0 (vlp16.hpp); the sweep starts at its first point.
  const std::vector<float> t = perception::times_from_azimuth(stripped, 1.0 / vlp16.rate_hz, vlp16.clockwise);
  ASSERT_EQ(t.size(), truth.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) worst = std::max(worst, std::abs(double{t[i]} - truth.time_offsets_s[i]));
  EXPECT_LT(worst, 1e-6);
  // The opposite direction turns the sweep around: the last column comes first.
  const std::vector<float> ccw = perception::times_from_azimuth(stripped, 0.1, false);
  EXPECT_GT(std::abs(double{ccw.back()} - truth.time_offsets_s.back()), 0.09);
}

TEST(ScanReconstruction, KeepsTheCloudsOwnRings) {
  PointCloud c;
  c.points = {{10, 0, 0}, {10, 0, 1}};
  c.rings = {7, 9};
  const perception::RingReconstruction r = perception::reconstruct_rings(c, perception::lidar_model("hdl32"));
  EXPECT_EQ(r.method, perception::RingMethod::from_cloud);
  EXPECT_EQ(r.rings, c.rings);
}

namespace {

// A synthetic HDL-64E sweep stored line by line as KITTI stores it (each line from -pi to +pi,
// counter-clockwise, the top laser first), with a point at each seam jittering across it. Each
// laser sits `block_offset_m` above (upper block) or below the origin, so that the elevations seen
// from the origin change with range, and is tilted by `elevation_error_deg(laser)` from the
// nominal table (a unit's calibration).
template <class ElevationError>
PointCloud kitti_like_sweep(double block_offset_m, ElevationError elevation_error_deg,
                            std::vector<std::uint16_t>& line_of_point) {
  const perception::LidarModel m = perception::lidar_model("hdl64");
  PointCloud c;
  for (int line = 0; line < 64; ++line) {
    const int laser = 63 - line;
    const double el = m.elevations_rad[static_cast<std::size_t>(laser)] + deg2rad(elevation_error_deg(laser));
    const double height = laser < 32 ? -block_offset_m : block_offset_m;
    for (int k = 0; k < 2000; ++k) {
      double az = -std::numbers::pi + 2.0 * std::numbers::pi * (k + 0.5) / 2000.0;
      if (k == 1) az = std::numbers::pi - 1e-4;  // jitter across the seam
      const double range = 6.0 + 20.0 * (0.5 + 0.5 * std::sin(3.0 * az + line));
      const double horizontal = range * std::cos(el);
      c.points.emplace_back(static_cast<float>(horizontal * std::cos(az)),
                            static_cast<float>(horizontal * std::sin(az)),
                            static_cast<float>(height + range * std::sin(el)));
      line_of_point.push_back(static_cast<std::uint16_t>(line));
    }
  }
  return c;
}

double no_error(int) { return 0.0; }

}  // namespace

TEST(ScanReconstruction, Hdl64RingsFromTheStreamOrderOfAKittiSweep) {
  std::vector<std::uint16_t> truth;
  const PointCloud c = kitti_like_sweep(0.1, no_error, truth);
  const perception::RingReconstruction r = perception::reconstruct_rings(c, perception::lidar_model("hdl64"));
  EXPECT_EQ(r.method, perception::RingMethod::scan_order);
  EXPECT_EQ(r.ring_count, 64u);
  EXPECT_EQ(r.rings, truth);
}

TEST(ScanReconstruction, Hdl64RingsFromElevationClustersWhenTheOrderIsLost) {
  // A unit 0.5 deg off the nominal table, each laser another +-0.08 deg, its points stored column
  // by column (firing order): the stream order gives no lines and the nominal table's nearest beam
  // is the wrong one for most points, but each laser's elevations form their own cluster.
  const auto calibration = [](int laser) { return 0.5 + 0.08 * std::sin(7.0 * laser); };
  std::vector<std::uint16_t> line_of;
  const PointCloud by_line = kitti_like_sweep(0.0, calibration, line_of);
  PointCloud c;
  std::vector<std::uint16_t> expected;
  for (std::size_t k = 0; k < 2000; ++k) {
    if (k == 1) continue;  // the seam's point would be out of column order
    for (std::size_t line = 0; line < 64; ++line) {
      c.points.push_back(by_line.points[line * 2000 + k]);
      expected.push_back(static_cast<std::uint16_t>(63 - line));  // ring 0 = the lowest beam
    }
  }
  const perception::LidarModel m = perception::lidar_model("hdl64");
  const perception::RingReconstruction r = perception::reconstruct_rings(c, m);
  EXPECT_EQ(r.method, perception::RingMethod::elevation_clusters);
  EXPECT_EQ(r.ring_count, 64u);
  EXPECT_EQ(r.rings, expected);
  const std::vector<std::uint16_t> table = perception::rings_from_beam_table(c, m.elevations_rad);
  std::size_t table_right = 0;
  for (std::size_t i = 0; i < c.size(); ++i) table_right += table[i] == expected[i] ? 1 : 0;
  EXPECT_LT(table_right, c.size() / 2);
}

TEST(ScanReconstruction, RejectsABadPeriodAndAnUnknownModel) {
  EXPECT_THROW(perception::times_from_azimuth(PointCloud{}, 0.0, true), Error);
  EXPECT_THROW(perception::lidar_model("vlp32"), Error);
}
