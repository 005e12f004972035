#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bipednav/sim/gaussian_noise.hpp"
#include "bipednav/sim/raycaster.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::sim;

TEST(RayPacket, PerRayOriginsAgreeWithSingleRaysIncludingActorsAndPartialPackets) {
  World w;
  w.statics.push_back({"ground", SE3::Identity(), Plane{}});
  w.statics.push_back({"wall", make_se3(5.0, 0, 1.0, 0, 0, 0.3), Box{{0.2, 8.0, 2.0}}});
  Actor a;
  a.name = "mover";
  a.parts.push_back({"box", SE3::Identity(), Box{{0.3, 0.3, 2.0}}});
  a.trajectory = {{0.0, make_se3(2.5, 0.5, 1.0, 0, 0, 0)}, {10.0, make_se3(2.5, -0.5, 1.0, 0, 0, 0)}};
  a.loop = false;
  w.actors.push_back(a);
  RayCaster rc(w);
  rc.set_time(3.0);
  for (const int count : {16, 11, 1}) {
    RayPacket p;
    p.count = count;
    for (int i = 0; i < count; ++i) {
      // Origins moving along y, directions fanning out in azimuth and elevation.
      const Eigen::Vector3f o(0.1f * i, -0.8f + 0.1f * i, 1.0f + 0.02f * i);
      const Eigen::Vector3f d = Eigen::Vector3f(1.0f, 0.05f * (i - 8), 0.03f * (i % 5) - 0.08f).normalized();
      p.org_x[i] = o.x(), p.org_y[i] = o.y(), p.org_z[i] = o.z();
      p.dir_x[i] = d.x(), p.dir_y[i] = d.y(), p.dir_z[i] = d.z();
    }
    std::vector<float> ranges(16, -1.0f);
    rc.cast_packet(p, 30.0f, ranges.data(), count > 1);
    int hits_mover = 0;
    for (int i = 0; i < count; ++i) {
      const Eigen::Vector3d o(p.org_x[i], p.org_y[i], p.org_z[i]), d(p.dir_x[i], p.dir_y[i], p.dir_z[i]);
      const float single = rc.cast(o, d, 30.0f);
      EXPECT_NEAR(ranges[i], single, 1e-5f * (1.0f + single)) << count << " " << i;
      if (single < 2.6f) ++hits_mover;
    }
    for (int i = count; i < 16; ++i) EXPECT_EQ(ranges[i], -1.0f);  // inactive lanes are not written
    if (count == 16) {
      EXPECT_GT(hits_mover, 0);
    }
  }
  RayPacket empty;
  float r = -1.0f;
  rc.cast_packet(empty, 30.0f, &r);
  EXPECT_EQ(r, -1.0f);
}

TEST(GaussianNoise, SkipLandsWhereDrawsWould) {
  for (int offset = 0; offset < 5; ++offset)
    for (const std::uint64_t n : {0u, 1u, 2u, 3u, 4u, 5u, 7u, 1001u, 101760u}) {
      GaussianNoise a(3), b(3);
      for (int i = 0; i < offset; ++i) (void)a(), (void)b();
      a.skip(n);
      for (std::uint64_t i = 0; i < n; ++i) (void)b();
      for (int i = 0; i < 9; ++i) ASSERT_EQ(a(), b()) << "offset " << offset << ", n " << n << ", draw " << i;
    }
}

TEST(GaussianNoise, FillMatchesSingleDrawsAndIsStandardNormal) {
  GaussianNoise a(7), b(7);
  std::vector<float> block(1001);
  (void)a(), (void)b();  // fill() also works from the middle of a splitmix output
  a.fill(block);
  for (const float x : block) ASSERT_EQ(x, b());
  EXPECT_EQ(a(), b());
  GaussianNoise n(11);
  double sum = 0, sum2 = 0;
  const int count = 200000;
  for (int i = 0; i < count; ++i) {
    const double x = n();
    sum += x, sum2 += x * x;
  }
  const double mean = sum / count;
  EXPECT_NEAR(mean, 0.0, 0.02);
  EXPECT_NEAR(std::sqrt(sum2 / count - mean * mean), 1.0, 0.03);
  GaussianNoise c(7);
  (void)c();
  EXPECT_EQ(c(), block[0]);
}

}  // namespace
