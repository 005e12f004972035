#include "bipednav/sim/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "bipednav/common/error.hpp"
#include "bipednav/io/robot_profile_yaml.hpp"
#include "test_data.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::sim;

World small_room() {
  World w;
  w.statics.push_back({"n", make_se3(0, 4, 1.5, 0, 0, 0), Box{{8, 0.1, 3}}});
  w.statics.push_back({"s", make_se3(0, -4, 1.5, 0, 0, 0), Box{{8, 0.1, 3}}});
  w.statics.push_back({"e", make_se3(4, 0, 1.5, 0, 0, 0), Box{{0.1, 8, 3}}});
  w.statics.push_back({"pillar", make_se3(2, 1, 1, 0, 0, 0), Cylinder{0.2, 2}});
  Actor a;
  a.name = "cube";
  a.parts.push_back({"box", SE3::Identity(), Box{{0.3, 0.3, 0.3}}});
  a.trajectory = {{0, make_se3(1, -1, 0.15, 0, 0, 0)}, {2, make_se3(1, 1, 0.15, 0, 0, 0)}};
  w.actors.push_back(a);
  return w;
}

RobotProfile digit() { return io::load_robot_profile(test::source_dir() / "config" / "digit.yaml"); }

SimulationParams small_params(std::uint64_t seed) {
  SimulationParams p;
  p.seed = seed;
  p.depth.width = 64;
  p.depth.height = 36;
  return p;
}

struct Recording {
  std::vector<PointCloud> lidar;
  std::vector<DepthCloud> depth;
  std::vector<Odometry> odom;
};

Recording run(std::uint64_t seed, int steps) {
  Simulation sim(small_room(), digit(), Pose2{-1, 0, 0.2}, small_params(seed));
  Recording r;
  for (int i = 0; i < steps; ++i) {
    SensorFrame f = sim.step(Twist{0.4, 0.0, 0.3});
    if (f.lidar) r.lidar.push_back(*f.lidar);
    for (auto& d : f.depth) r.depth.push_back(d);
    if (f.odometry) r.odom.push_back(*f.odometry);
  }
  return r;
}

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(Simulation, SameSeedIsBitIdenticalDifferentSeedDiffers) {
  const Recording a = run(7, 25), b = run(7, 25), c = run(8, 25);
  ASSERT_EQ(a.lidar.size(), 2u);
  ASSERT_EQ(a.depth.size(), 2u * 4u);  // two cameras at t = 0, 1/15, 2/15, 3/15
  for (std::size_t i = 0; i < a.lidar.size(); ++i) {
    EXPECT_TRUE(same_bytes(a.lidar[i].points, b.lidar[i].points));
    EXPECT_TRUE(same_bytes(a.lidar[i].time_offsets_s, b.lidar[i].time_offsets_s));
    EXPECT_FALSE(same_bytes(a.lidar[i].points, c.lidar[i].points));
  }
  for (std::size_t i = 0; i < a.depth.size(); ++i) {
    EXPECT_TRUE(same_bytes(a.depth[i].cloud.points, b.depth[i].cloud.points));
    EXPECT_FALSE(same_bytes(a.depth[i].cloud.points, c.depth[i].cloud.points));
  }
  ASSERT_EQ(a.odom.size(), b.odom.size());
  for (std::size_t i = 0; i < a.odom.size(); ++i) {
    EXPECT_EQ(a.odom[i].T_odom_base.x, b.odom[i].T_odom_base.x);
    EXPECT_EQ(a.odom[i].roll_rad, b.odom[i].roll_rad);
  }
  EXPECT_NE(a.odom.back().T_odom_base.x, c.odom.back().T_odom_base.x);
}

TEST(Simulation, RecycledFramesGiveTheSameClouds) {
  // Handing frames back (their buffers then hold later clouds) changes no output.
  const Recording a = run(7, 25);
  Simulation sim(small_room(), digit(), Pose2{-1, 0, 0.2}, small_params(7));
  Recording b;
  const void* recycled_depth = nullptr;
  bool reused = false;
  for (int i = 0; i < 25; ++i) {
    SensorFrame f = sim.step(Twist{0.4, 0.0, 0.3});
    if (f.lidar) b.lidar.push_back(*f.lidar);
    for (auto& d : f.depth) {
      b.depth.push_back(d);
      reused = reused || d.cloud.points.data() == recycled_depth;
    }
    if (!f.depth.empty()) recycled_depth = f.depth.back().cloud.points.data();
    sim.recycle(std::move(f));
  }
  EXPECT_TRUE(reused);
  ASSERT_EQ(b.lidar.size(), a.lidar.size());
  for (std::size_t i = 0; i < a.lidar.size(); ++i) {
    EXPECT_TRUE(same_bytes(a.lidar[i].points, b.lidar[i].points));
    EXPECT_TRUE(same_bytes(a.lidar[i].time_offsets_s, b.lidar[i].time_offsets_s));
    EXPECT_TRUE(same_bytes(a.lidar[i].rings, b.lidar[i].rings));
    EXPECT_EQ(a.lidar[i].stamp_s, b.lidar[i].stamp_s);
  }
  ASSERT_EQ(b.depth.size(), a.depth.size());
  for (std::size_t i = 0; i < a.depth.size(); ++i) {
    EXPECT_EQ(a.depth[i].camera, b.depth[i].camera);
    EXPECT_EQ(a.depth[i].cloud.frame_id, b.depth[i].cloud.frame_id);
    EXPECT_EQ(a.depth[i].cloud.stamp_s, b.depth[i].cloud.stamp_s);
    EXPECT_TRUE(same_bytes(a.depth[i].cloud.points, b.depth[i].cloud.points));
  }
}

TEST(Simulation, FramesCarryTheScheduledData) {
  Simulation sim(small_room(), digit(), Pose2{-1, 0, 0}, small_params(1));
  EXPECT_EQ(sim.world().statics.back().name, "ground_plane");  // added
  int lidar = 0, depth = 0, odom = 0;
  for (int i = 0; i < 100; ++i) {
    const SensorFrame f = sim.step(Twist{0.3, 0, 0});
    EXPECT_NEAR(f.stamp_s, 0.01 * (i + 1), 1e-12);
    if (f.lidar) {
      ++lidar;
      EXPECT_EQ(f.lidar->frame_id, "lidar");
      EXPECT_NEAR(f.lidar->stamp_s, 0.1 * (lidar - 1), 1e-9);
      EXPECT_TRUE(f.lidar->has_time() && f.lidar->has_ring() && f.lidar->is_consistent());
      EXPECT_GT(f.lidar->size(), 20000u);
    }
    for (const DepthCloud& d : f.depth) {
      ++depth;
      EXPECT_TRUE(d.camera == "depth_front" || d.camera == "depth_back");
      EXPECT_EQ(d.cloud.frame_id, d.camera);
      EXPECT_EQ(d.cloud.size(), 64u * 36u);
      EXPECT_LE(d.cloud.stamp_s, f.stamp_s);
    }
    if (f.odometry) ++odom;
  }
  EXPECT_EQ(lidar, 10);
  EXPECT_EQ(depth, 2 * 15);
  EXPECT_EQ(odom, 50);
  EXPECT_NEAR(sim.now_s(), 1.0, 1e-12);
  EXPECT_GT(sim.true_pose().x, -1.0 + 0.1);
  ASSERT_EQ(sim.actor_poses().size(), 1u);
  EXPECT_NEAR(sim.actor_poses()[0].translation().y(), 0.0, 1e-9);  // half-way at t = 1 s
  EXPECT_NEAR(sim.T_world_sensor("lidar").translation().z(), 1.474, 1e-9);
  EXPECT_THROW(sim.T_world_sensor("sonar"), Error);
}

TEST(Simulation, ExistingGroundPlaneIsKeptAndOptionsRespected) {
  World w = small_room();
  w.statics.push_back({"floor", SE3::Identity(), Plane{}});
  EXPECT_FALSE(ensure_ground_plane(w));
  SimulationParams p = small_params(1);
  p.enable_lidar = false;
  p.enable_odometry = false;
  Simulation sim(w, digit(), Pose2{}, p);
  EXPECT_EQ(sim.world().statics.size(), w.statics.size());
  for (int i = 0; i < 20; ++i) {
    const SensorFrame f = sim.step(Twist{});
    EXPECT_FALSE(f.lidar);
    EXPECT_FALSE(f.odometry);
  }
}

TEST(Simulation, RejectsBadInput) {
  SimulationParams p;
  p.step_s = 0.0;
  EXPECT_THROW(Simulation(small_room(), digit(), Pose2{}, p), ParamError);
  p = {};
  p.step_s = 0.2;  // longer than a LiDAR sweep
  EXPECT_THROW(Simulation(small_room(), digit(), Pose2{}, p), ParamError);
  p = {};
  p.depth.width = 0;
  EXPECT_THROW(Simulation(small_room(), digit(), Pose2{}, p), ParamError);
  RobotProfile bad = digit();
  bad.footprint_radius_m = 0;
  EXPECT_THROW(Simulation(small_room(), bad, Pose2{}, small_params(1)), ParamError);
  Simulation sim(small_room(), digit(), Pose2{}, small_params(1));
  EXPECT_THROW(sim.step(Twist{INFINITY, 0, 0}), Error);
  EXPECT_THROW(Simulation(small_room(), digit(), Pose2{NAN, 0, 0}, small_params(1)), Error);
}

}  // namespace

TEST(Simulation, RecordsEveryContactOnceAtItsStart) {
  World w;
  w.statics.push_back({"e", make_se3(4, 0, 1.5, 0, 0, 0), Box{{0.1, 8, 3}}});
  SimulationParams p = small_params(1);
  p.enable_lidar = false;
  p.enable_depth = false;
  Simulation sim(w, digit(), Pose2{2.5, 0, 0}, p);
  EXPECT_TRUE(sim.contacts().empty());
  // Drives into the wall, scrapes on for a while, backs off clear, and drives in again.
  const auto drive_until = [&sim](const Twist& cmd, bool touching) {
    for (int i = 0; i < 3000 && sim.in_collision() != touching; ++i) sim.step(cmd);
    ASSERT_EQ(sim.in_collision(), touching);
  };
  const Twist forward{0.3, 0.0, 0.0}, back{-0.3, 0.0, 0.0};
  drive_until(forward, true);
  for (int i = 0; i < 50; ++i) sim.step(forward);
  EXPECT_TRUE(sim.in_collision());
  drive_until(back, false);
  for (int i = 0; i < 100; ++i) sim.step(back);
  drive_until(forward, true);
  ASSERT_EQ(sim.contacts().size(), 2u);
  ASSERT_TRUE(sim.first_collision());
  EXPECT_EQ(sim.first_collision()->time_s, sim.contacts().front().time_s);
  EXPECT_LT(sim.contacts()[0].time_s, sim.contacts()[1].time_s);
  for (const CollisionEvent& e : sim.contacts()) {
    EXPECT_EQ(e.obstacle, "e");
    EXPECT_NEAR(e.point.x(), 3.95, 0.02);
  }
}
