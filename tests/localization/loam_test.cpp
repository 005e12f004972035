#include "bipednav/localization/loam.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"
#include "synthetic_scene.hpp"

namespace bipednav::localization {
namespace {

using test::SweepSpec;
using test::synthetic_sweep;

double rotation_angle(const SE3& T) { return Eigen::AngleAxisd(T.rotation()).angle(); }

// Lidar 1.2 m above the floor, moving with constant body velocity (vx, vy, yaw rate) from `start`.
std::function<SE3(double)> constant_motion(const SE3& start, double vx, double vy, double wz) {
  return [=](double t) {
    Vector6d x;
    x << vx * t, vy * t, 0, 0, 0, wz * t;
    return start * motion_to_se3(x);
  };
}

// The features of the room swept from `pose_at` from t on, with 1 cm noise.
LoamFeatures room_features(const std::function<SE3(double)>& pose_at, double t, Rng& rng) {
  SweepSpec spec;
  spec.noise_m = 0.01;
  const FeatureParams fp;
  return extract_features(sanitize_sweep(synthetic_sweep(test::room_scene(), pose_at, t, spec, rng), fp), fp);
}

TEST(LoamFeatures, SmoothnessIsZeroOnALineAndLargeAtACorner) {
  std::vector<Eigen::Vector3f> line, corner;
  for (int i = -5; i <= 5; ++i) {
    line.emplace_back(3.0f, 0.05f * i, 0.0f);
    corner.emplace_back(3.0f - 0.05f * std::abs(i), 0.05f * i, 0.0f);
  }
  EXPECT_NEAR(ring_smoothness(line, 5)[5], 0.0, 1e-6);
  // eq. 4.5: |sum of (X_i - X_j)| / (|S| |X_i|) = |(1.5, 0, 0)| / (10 * 3)
  EXPECT_NEAR(ring_smoothness(corner, 5)[5], 1.5 / 30.0, 1e-6);
  EXPECT_LT(ring_smoothness(line, 5)[0], 0.0);  // not enough neighbours
}

TEST(LoamFeatures, RingsDerivedFromElevationWhenAbsent) {
  PointCloud c;
  c.points = {{10, 0, std::tan(-0.2617994f) * 10}, {10, 0, 0}, {10, 0, std::tan(0.2617994f) * 10}};
  const auto rings = ring_indices(c, FeatureParams{});
  EXPECT_EQ(rings[0], 0);
  EXPECT_TRUE(rings[1] == 7 || rings[1] == 8);
  EXPECT_EQ(rings[2], 15);
}

TEST(LoamFeatures, ExtractsPerRegionMaxima) {
  Rng rng(1);
  const auto scene = test::room_scene();
  const PointCloud sweep =
      synthetic_sweep(scene, constant_motion(make_se3(0, 0, 1.2, 0, 0, 0), 0, 0, 0), 0.0, SweepSpec{}, rng);
  FeatureParams p;
  const LoamFeatures f = extract_features(sanitize_sweep(sweep, p), p);
  EXPECT_GT(f.edges.size(), 20u);
  EXPECT_GT(f.planars.size(), 100u);
  EXPECT_LE(f.edges.size(), 16u * 4u * 2u);
  EXPECT_LE(f.planars.size(), 16u * 4u * 4u);
  EXPECT_GE(f.map_planars.size(), f.planars.size());
  EXPECT_EQ(f.edges.rings.size(), f.edges.size());
  EXPECT_EQ(f.planars.time_offsets_s.size(), f.planars.size());
}

TEST(LoamFeatures, SanitizedIsTheSweepItselfWhenNothingIsDropped) {
  PointCloud sweep;
  sweep.frame_id = "lidar";
  sweep.stamp_s = 2.5;
  sweep.points = {{1, 0, 0}, {0, 2, 0}, {0, 0, 3}};
  sweep.time_offsets_s = {0.0f, 0.01f, 0.02f};
  sweep.rings = {0, 1, 2};
  const FeatureParams p;
  PointCloud storage;
  EXPECT_EQ(&sanitized(sweep, p, storage), &sweep);
  EXPECT_TRUE(storage.empty());
  const auto same = [](const PointCloud& a, const PointCloud& b) {
    return a.points == b.points && a.time_offsets_s == b.time_offsets_s && a.rings == b.rings &&
           a.intensities == b.intensities && a.frame_id == b.frame_id && a.stamp_s == b.stamp_s;
  };
  EXPECT_TRUE(same(sanitize_sweep(sweep, p), sweep));
  // A non-finite time, a point too near and one too far: the sanitized copy.
  for (const int bad : {0, 1, 2}) {
    PointCloud s = sweep;
    if (bad == 0) s.time_offsets_s[1] = std::numeric_limits<float>::quiet_NaN();
    if (bad == 1) s.points[1] = {0.1f, 0, 0};
    if (bad == 2) s.points[1] = {200.0f, 0, 0};
    const PointCloud& clean = sanitized(s, p, storage);
    EXPECT_EQ(&clean, &storage);
    EXPECT_EQ(clean.size(), 2u);
    EXPECT_TRUE(same(clean, sanitize_sweep(s, p)));
  }
  sweep.rings.pop_back();
  EXPECT_THROW(sanitized(sweep, p, storage), Error);
}

TEST(LoamOdometry, DeskewUnderPureRotationRestoresTheEndFrame) {
  Rng rng(2);
  const auto scene = test::room_scene();
  const SE3 start = make_se3(0.5, -0.3, 1.2, 0, 0, 0.2);
  const double yaw_rate = 1.5;  // rad/s: 8.6 deg within one sweep
  const auto pose_at = constant_motion(start, 0, 0, yaw_rate);
  std::vector<Eigen::Vector3d> world;
  const PointCloud sweep = synthetic_sweep(scene, pose_at, 0.0, SweepSpec{}, rng, &world);
  const SE3 T_start_end = pose_at(0.0).inverse() * pose_at(0.1);
  const PointCloud deskewed = deskew_to_end(sweep, T_start_end, 0.1);
  const SE3 T_end_world = pose_at(0.1).inverse();
  double worst = 0.0, raw_worst = 0.0;
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const Eigen::Vector3d expected = T_end_world * world[i];
    worst = std::max(worst, (deskewed.points[i].cast<double>() - expected).norm());
    raw_worst = std::max(raw_worst, (sweep.points[i].cast<double>() - expected).norm());
  }
  EXPECT_LT(worst, 1e-4);
  EXPECT_GT(raw_worst, 0.3);  // the distortion really was there
}

TEST(LoamOdometry, RecoversSweepMotionFromIdentity) {
  Rng rng(3);
  const auto scene = test::room_scene();
  SweepSpec spec;
  spec.noise_m = 0.01;
  const auto pose_at = constant_motion(make_se3(-1, 0.5, 1.2, 0, 0, 0.3), 0.6, 0.1, 0.4);
  FeatureParams fp;
  LoamOdometry odo(OdometryParams{});
  const LoamFeatures f0 = extract_features(sanitize_sweep(synthetic_sweep(scene, pose_at, 0.0, spec, rng), fp), fp);
  const SE3 true0 = pose_at(0.0).inverse() * pose_at(0.1);
  odo.set_reference(f0, true0);
  const LoamFeatures f1 = extract_features(sanitize_sweep(synthetic_sweep(scene, pose_at, 0.1, spec, rng), fp), fp);
  const OdometryResult r = odo.estimate(f1, SE3::Identity());
  const SE3 truth = pose_at(0.1).inverse() * pose_at(0.2);
  const SE3 err = truth.inverse() * r.T_start_end;
  EXPECT_TRUE(r.matched);
  EXPECT_LE(r.degenerate_dims, 1);  // the height: the floor and ceiling are barely seen from 1.2 m
  EXPECT_LT(err.translation().norm(), 0.01);
  EXPECT_LT(rotation_angle(err), 0.006);
}

// OdometryParams::round_converged_*: stopping the rounds once a round's change is below 1 mm /
// 0.3 mrad (instead of 0.1 mm / 0.01 mrad) runs fewer rounds and keeps the estimate within the
// bounds above.
TEST(LoamOdometry, LooserRoundConvergenceStopsEarlierWithinTheSameBounds) {
  const auto pose_at = constant_motion(make_se3(-1, 0.5, 1.2, 0, 0, 0.3), 0.6, 0.1, 0.4);
  Rng rng(3);
  const LoamFeatures f0 = room_features(pose_at, 0.0, rng);
  const LoamFeatures f1 = room_features(pose_at, 0.1, rng);
  const SE3 truth = pose_at(0.1).inverse() * pose_at(0.2);
  const auto run = [&](const OdometryParams& p) {
    LoamOdometry odo(p);
    odo.set_reference(f0, pose_at(0.0).inverse() * pose_at(0.1));
    return odo.estimate(f1, SE3::Identity());
  };
  OdometryParams loose;
  loose.round_converged_translation_m = 1e-3;
  loose.round_converged_rotation_rad = 3e-4;
  const OdometryResult tight = run(OdometryParams{}), r = run(loose);
  const SE3 err = truth.inverse() * r.T_start_end;
  EXPECT_TRUE(r.matched);
  EXPECT_LT(r.rounds, tight.rounds);
  EXPECT_LE(r.degenerate_dims, 1);
  EXPECT_LT(err.translation().norm(), 0.01);
  EXPECT_LT(rotation_angle(err), 0.006);
}

// Each odometry keeps its own kd-trees and hints: two of them fed interleaved sweeps on one thread
// estimate what each does alone, bit for bit. B's guesses are 2 cm off A's, so a reference tree
// left by A (built a few cm from where B has its points) would pass B's rebuild test and be searched.
TEST(LoamOdometry, TwoOdometriesInterleavedEstimateAsEachAlone) {
  const auto pose_at = constant_motion(make_se3(-1, 0.5, 1.2, 0, 0, 0.3), 0.6, 0.1, 0.4);
  Rng rng(5);
  std::vector<LoamFeatures> f;
  std::vector<SE3> truth;
  for (int k = 0; k < 4; ++k) {
    f.push_back(room_features(pose_at, 0.1 * k, rng));
    truth.push_back(pose_at(0.1 * k).inverse() * pose_at(0.1 * (k + 1)));
  }
  const SE3 offset = make_se3(0.02, 0, 0, 0, 0, 0);
  const auto step = [&](LoamOdometry& odo, std::size_t k, const SE3& guess_offset) {
    odo.set_reference(f[k - 1], truth[k - 1]);
    return odo.estimate(f[k], truth[k - 1] * guess_offset).T_start_end;
  };
  std::vector<SE3> alone_a, alone_b;
  LoamOdometry b(OdometryParams{});
  for (std::size_t k = 1; k < f.size(); ++k) alone_b.push_back(step(b, k, offset));
  LoamOdometry a(OdometryParams{});
  for (std::size_t k = 1; k < f.size(); ++k) alone_a.push_back(step(a, k, SE3::Identity()));
  LoamOdometry a2(OdometryParams{}), b2(OdometryParams{});
  for (std::size_t k = 1; k < f.size(); ++k) {
    const SE3 ra = step(a2, k, SE3::Identity()), rb = step(b2, k, offset);
    EXPECT_EQ(ra.matrix(), alone_a[k - 1].matrix()) << k;
    EXPECT_EQ(rb.matrix(), alone_b[k - 1].matrix()) << k;
  }
}

TEST(Loam, DrivesARoomWithSmallDrift) {
  Rng rng(4);
  const auto scene = test::room_scene();
  SweepSpec spec;
  spec.noise_m = 0.02;
  // A loop: forward and turning, 0.5 m/s for 12 s.
  const auto pose_at = [](double t) {
    Vector6d x;
    const double wz = 0.35;
    x << 0, 0, 0, 0, 0, wz * t;
    const double r = 0.5 / wz;
    SE3 T = make_se3(-2.0 + r * std::sin(wz * t), -1.0 + r * (1.0 - std::cos(wz * t)), 1.2, 0, 0, wz * t);
    return T;
  };
  LoamParams p;
  Loam loam(p);
  const SE3 T0 = pose_at(0.1);
  SE3 last;
  double travelled = 0.0;
  for (int k = 0; k < 120; ++k) {
    const LoamOutput out = loam.process(synthetic_sweep(scene, pose_at, 0.1 * k, spec, rng));
    ASSERT_TRUE(out.healthy) << "sweep " << k << ": " << out.reason;
    ASSERT_TRUE(out.T_world_lidar.matrix().allFinite());
    last = out.T_world_lidar;
    if (k > 0) travelled += (pose_at(0.1 * (k + 1)).translation() - pose_at(0.1 * k).translation()).norm();
  }
  const SE3 truth = T0.inverse() * pose_at(0.1 * 120);
  const SE3 err = truth.inverse() * last;
  // Planar drift within 1 % of the distance; the height is barely observable from 1.2 m in a 3 m
  // high room (the floor is seen beyond 4.5 m only), so it is bounded loosely.
  EXPECT_LT(err.translation().head<2>().norm(), 0.01 * travelled);
  EXPECT_LT(std::abs(matrix_to_rpy(err.rotation()).z()), 0.01);
  EXPECT_LT(rotation_angle(err), 0.03);
  EXPECT_LT(std::abs(err.translation().z()), 0.15);
  EXPECT_GT(loam.map_size(), 100u);
}

TEST(Loam, EmptyNanAndFeaturelessSweepsAreUnhealthyButFinite) {
  Loam loam;
  PointCloud empty;
  LoamOutput out = loam.process(empty);
  EXPECT_FALSE(out.healthy);
  EXPECT_NE(out.reason.find("empty"), std::string::npos);
  EXPECT_TRUE(out.T_world_lidar.matrix().allFinite());

  PointCloud nans;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int i = 0; i < 100; ++i) nans.points.emplace_back(nan, 1.0f, nan);
  out = loam.process(nans, make_se3(0.1, 0, 0, 0, 0, 0));
  EXPECT_FALSE(out.healthy);
  EXPECT_NE(out.reason.find("no valid points"), std::string::npos);
  EXPECT_NEAR(out.T_world_lidar.translation().x(), 0.1, 1e-12);  // the prior carried the pose

  PointCloud few;  // a handful of points on a circle: no usable features
  for (int i = 0; i < 8; ++i) few.points.emplace_back(5.0f * std::cos(0.7f * i), 5.0f * std::sin(0.7f * i), 0.0f);
  out = loam.process(few);
  EXPECT_FALSE(out.healthy);
  EXPECT_NE(out.reason.find("too few features"), std::string::npos);
  EXPECT_TRUE(out.T_world_lidar.matrix().allFinite());

  const Eigen::Vector3d nan_prior(nan, 0, 0);
  SE3 bad = SE3::Identity();
  bad.translation() = nan_prior;
  out = loam.process(few, bad);
  EXPECT_TRUE(out.T_world_lidar.matrix().allFinite());
}

TEST(Loam, NanPointsInsideAGoodSweepAreDropped) {
  Rng rng(5);
  const auto scene = test::room_scene();
  const auto pose_at = constant_motion(make_se3(0, 0, 1.2, 0, 0, 0), 0.3, 0, 0);
  Loam loam;
  for (int k = 0; k < 3; ++k) {
    PointCloud s = synthetic_sweep(scene, pose_at, 0.1 * k, SweepSpec{}, rng);
    for (std::size_t i = 0; i < s.size(); i += 50) s.points[i].x() = std::numeric_limits<float>::quiet_NaN();
    const LoamOutput out = loam.process(s);
    EXPECT_TRUE(out.healthy) << out.reason;
    for (const auto& q : out.deskewed.points) ASSERT_TRUE(q.allFinite());
  }
}

TEST(Loam, CorridorIsDegenerateAndKeepsThePriorAlongTheAxis) {
  Rng rng(6);
  const auto scene = test::corridor_scene();
  const auto pose_at = constant_motion(make_se3(0, 0, 1.2, 0, 0, 0), 0.5, 0, 0);
  Loam loam;
  const SE3 prior = make_se3(0.05, 0, 0, 0, 0, 0);  // exactly the true motion per sweep
  LoamOutput out;
  for (int k = 0; k < 5; ++k) out = loam.process(synthetic_sweep(scene, pose_at, 0.1 * k, SweepSpec{}, rng), prior);
  EXPECT_TRUE(out.degenerate) << out.reason;
  EXPECT_TRUE(out.healthy) << out.reason;
  EXPECT_NEAR(out.T_world_lidar.translation().x(), 0.2, 0.02);
  EXPECT_NEAR(out.T_world_lidar.translation().y(), 0.0, 0.02);
}

// The map match tells which horizontal directions it observed: none along a corridor's axis
// (the walls fix y, nothing fixes x), both in a room. Mapping runs on sweeps 1, 11, 21, ...; the
// first only inserts.
Eigen::Matrix2d unobserved_after_second_mapping(const test::SyntheticScene& scene) {
  Rng rng(7);
  const auto pose_at = constant_motion(make_se3(0, 0, 1.2, 0, 0, 0), 0.5, 0, 0);
  Loam loam;
  const SE3 prior = make_se3(0.05, 0, 0, 0, 0, 0);
  LoamOutput out;
  for (int k = 0; k < 12; ++k) out = loam.process(synthetic_sweep(scene, pose_at, 0.1 * k, SweepSpec{}, rng), prior);
  EXPECT_TRUE(out.mapped);
  return out.unobserved_xy;
}

TEST(Loam, ReportsTheCorridorAxisAsTheUnobservedHorizontalDirection) {
  const Eigen::Matrix2d weak = unobserved_after_second_mapping(test::corridor_scene());
  EXPECT_NEAR(weak(0, 0), 1.0, 0.05);  // along x
  EXPECT_NEAR(weak(1, 1), 0.0, 0.05);
  EXPECT_NEAR(weak(0, 1), 0.0, 0.05);
}

TEST(Loam, ReportsNoUnobservedHorizontalDirectionInARoom) {
  EXPECT_TRUE(unobserved_after_second_mapping(test::room_scene()).isZero(1e-9));
}

TEST(Loam, ParamsAreValidated) {
  LoamParams p;
  p.features.sub_regions = 0;
  EXPECT_THROW(Loam{p}, ParamError);
  p = LoamParams{};
  p.odometry.scan_period_s = 0;
  EXPECT_THROW(Loam{p}, ParamError);
}

}  // namespace
}  // namespace bipednav::localization
