#include <gtest/gtest.h>

#include <limits>

#include "bipednav/common/error.hpp"
#include "bipednav/perception/fusion.hpp"
#include "bipednav/perception/pass_through.hpp"

namespace bipednav::perception {
namespace {

TEST(PassThrough, RangeNanAndHeightBand) {
  PointCloud c;
  const float q = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  c.points = {{1, 0, 0}, {3, 0, 0}, {q, 0, 0}, {0, inf, 0}, {0, 0, -0.1f}, {0, 2, 1.9f}, {0.5f, 0, 0.5f}};
  c.intensities = {1, 2, 3, 4, 5, 6, 7};
  PassThroughParams p;
  p.max_range_m = 2.9;
  PointCloud r = pass_through(c, p);
  EXPECT_EQ(r.intensities, (std::vector<float>{1, 5, 6, 7}));
  p.min_height_m = -0.05;  // drop what lies below the ground
  p.max_height_m = 1.0;    // and what is above the robot
  r = pass_through(c, p);
  EXPECT_EQ(r.intensities, (std::vector<float>{1, 7}));
  // Ranges are measured from the sensor origin, heights from the given plane (z = 0.5 here).
  p = PassThroughParams{};
  p.max_range_m = 1.0;
  p.min_height_m = 0.0;
  r = pass_through(c, p, Eigen::Vector3f(3, 0, 0), Plane(0, 0, 2, -1));
  EXPECT_EQ(r.intensities, (std::vector<float>{}));
  r = pass_through(c, p, Eigen::Vector3f(0, 2, 2), Plane(0, 0, 2, -1));
  EXPECT_EQ(r.intensities, (std::vector<float>{6}));
}

TEST(PassThrough, EmptyAndBadParams) {
  EXPECT_TRUE(pass_through(PointCloud{}, PassThroughParams{}).empty());
  PassThroughParams p;
  p.min_range_m = 3.0;
  p.max_range_m = 2.0;
  EXPECT_THROW(pass_through(PointCloud{}, p), ParamError);
  p = PassThroughParams{};
  p.min_height_m = 1.0;
  p.max_height_m = 0.0;
  EXPECT_THROW(pass_through(PointCloud{}, p), ParamError);
}

TEST(Fusion, TransformsAndKeepsSources) {
  FusedCloud f;
  PointCloud a, b;
  a.points = {{1, 0, 0}, {std::numeric_limits<float>::quiet_NaN(), 0, 0}};
  b.points = {{0, 0, 1}, {2, 0, 0}};
  const SE3 T_a = make_se3(0.1, 0, 1.0, 0, M_PI / 4, 0);  // pitched 45 deg down
  const SE3 T_b = make_se3(0, 0, 1.5, 0, 0, M_PI);        // facing backwards
  EXPECT_EQ(append_sensor_cloud(f, a, T_a, "depth_front", 2.9), 0u);
  EXPECT_EQ(append_sensor_cloud(f, b, T_b, "lidar", 100.0), 1u);
  ASSERT_EQ(f.size(), 3u);
  EXPECT_TRUE(f.cloud.points[0].isApprox(Eigen::Vector3f(0.1f + std::sqrt(0.5f), 0.0f, 1.0f - std::sqrt(0.5f))));
  EXPECT_TRUE(f.cloud.points[1].isApprox(Eigen::Vector3f(0.0f, 0.0f, 2.5f)));
  EXPECT_TRUE(f.cloud.points[2].isApprox(Eigen::Vector3f(-2.0f, 0.0f, 1.5f)));
  EXPECT_EQ(f.source, (std::vector<std::uint8_t>{0, 1, 1}));
  ASSERT_EQ(f.sources.size(), 2u);
  EXPECT_EQ(f.sources[1].name, "lidar");
  EXPECT_TRUE(f.sources[0].origin_base.isApprox(Eigen::Vector3d(0.1, 0, 1.0)));
  EXPECT_EQ(f.sources[0].max_range_m, 2.9);
}

}  // namespace
}  // namespace bipednav::perception
