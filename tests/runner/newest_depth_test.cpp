// NavigatorParams::newest_depth_only: each local map update integrates only the newest frame of
// each depth camera, and the superseded frames are not processed.
#include <gtest/gtest.h>

#include <cstdio>

#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/navigation/navigator.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/simulation.hpp"
#include "test_data.hpp"

using namespace bipednav;

namespace {

SE3 at(double x, double y, double z) {
  SE3 T = SE3::Identity();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

struct BoxWatch {
  std::uint8_t box_cell_before = 0, box_cell_after = 0;  // the box's first cell in observed()
  bool ground_from_ransac = false;
  std::size_t skipped = 0, depth_frames = 0;
  double cleared_at_s = -1.0;  // when the box's cell was first free again after it began to move
};

// A stationary TurtleBot3 (no goal) with a 0.3 m box 1 m ahead in the front camera's view (under
// the LiDAR, which passes over it). At t = 2 s the box slides 3 m sideways, out of the camera's
// view, within 1 s: the camera's floor returns must clear its cells.
BoxWatch watch_box_leave(bool newest_depth_only) {
  const RobotProfile robot = navigation::load_robot("turtlebot3");
  runner::RunOptions o;
  navigation::NavigatorParams params = runner::navigator_params(robot, o);
  params.newest_depth_only = newest_depth_only;
  sim::World world;
  world.name = "box_leaves";
  sim::Actor box;
  box.name = "box";
  box.parts.push_back({"body", at(0.0, 0.0, 0.15), sim::Box{{0.3, 0.3, 0.3}}});
  box.trajectory = {{0.0, at(1.0, 0.0, 0.0)}, {2.0, at(1.0, 0.0, 0.0)}, {3.0, at(1.0, 3.0, 0.0)}};
  box.loop = false;
  world.actors.push_back(box);
  const Pose2 start{0.0, 0.0, 0.0};
  sim::Simulation sim(world, robot, start, {});
  navigation::Navigator nav(params, robot, mapping::GridGeometry{200, 200, 0.05, -5.0, -5.0}, start);
  BoxWatch out;
  const auto box_cell = [&] {
    const auto& m = nav.local_map().observed();
    const auto c = m.geometry().world_to_cell(0.9, 0.0);  // the box's near face
    return m.cost(c->x, c->y);
  };
  Twist cmd;
  while (sim.now_s() < 5.0) {
    SensorFrame frame = sim.step(cmd);
    out.depth_frames += frame.depth.size();
    cmd = nav.tick(frame);
    if (std::abs(sim.now_s() - 1.9) < 1e-6) out.box_cell_before = box_cell();
    if (sim.now_s() > 2.0 && out.cleared_at_s < 0.0 && box_cell() == mapping::kFree) out.cleared_at_s = sim.now_s();
    sim.recycle(std::move(frame));
  }
  out.box_cell_after = box_cell();
  out.ground_from_ransac = nav.last_perception().plane_from_ransac;
  out.skipped = nav.depth_frames_skipped();
  return out;
}

}  // namespace

TEST(NewestDepthOnly, AnObstacleThatMovesAwayIsClearedAndOneFrameInThreeIsSkipped) {
  const BoxWatch on = watch_box_leave(true);
  EXPECT_EQ(on.box_cell_before, mapping::kLethal);
  EXPECT_EQ(on.box_cell_after, mapping::kFree);
  EXPECT_TRUE(on.ground_from_ransac);
  // Two 15 Hz cameras, a 10 Hz map: each update keeps one frame per camera, a third are skipped.
  EXPECT_GE(on.depth_frames, 140u);
  EXPECT_NEAR(static_cast<double>(on.skipped), on.depth_frames / 3.0, 4.0);
  const BoxWatch off = watch_box_leave(false);
  EXPECT_EQ(off.box_cell_before, mapping::kLethal);
  EXPECT_EQ(off.box_cell_after, mapping::kFree);
  EXPECT_EQ(off.skipped, 0u);
  // Cleared as soon as without the policy, within one update (the box has left the cell by ~2.1 s).
  EXPECT_GT(on.cleared_at_s, 2.0);
  EXPECT_LE(on.cleared_at_s, off.cleared_at_s + 0.1 + 1e-9);
  std::printf("box cell cleared at %.2f s (newest_depth_only) and %.2f s (every frame)\n", on.cleared_at_s,
              off.cleared_at_s);
}

// The runner lets the simulator ask the navigator before rendering each depth image
// (Simulation::set_depth_demand, Navigator::wants_depth): the images newest_depth_only would drop
// are not rendered, and the run is the same bit for bit.
TEST(NewestDepthOnly, ImagesTheNavigatorWouldDropAreNotRenderedAndTheRunIsTheSame) {
  const sim::Scenario s = sim::load_scenario(test::source_dir() / "scenarios" / "hexagon_static.yaml");
  runner::RunOptions o;
  o.robot = "turtlebot3";
  o.time_limit_s = 8.0;
  const runner::RunResult lazy = runner::run_scenario(s, o);
  o.render_unused_depth = true;
  const runner::RunResult every = runner::run_scenario(s, o);
  ASSERT_EQ(lazy.trace.size(), every.trace.size());
  for (std::size_t i = 0; i < lazy.trace.size(); ++i) {
    ASSERT_EQ(lazy.trace[i].true_pose, every.trace[i].true_pose) << "sample " << i;
    ASSERT_EQ(lazy.trace[i].estimated_pose, every.trace[i].estimated_pose) << "sample " << i;
    ASSERT_EQ(lazy.trace[i].cmd.linear_x, every.trace[i].cmd.linear_x) << "sample " << i;
    ASSERT_EQ(lazy.trace[i].cmd.angular_z, every.trace[i].cmd.angular_z) << "sample " << i;
  }
  EXPECT_EQ(lazy.replans, every.replans);
  EXPECT_EQ(lazy.min_clearance_m, every.min_clearance_m);
  // The same images are used; the dropped third is no longer rendered.
  EXPECT_EQ(lazy.depth_images_unused, every.depth_images_unused);
  EXPECT_GT(every.depth_images_unused, every.depth_images / 4);
  EXPECT_EQ(lazy.depth_images + lazy.depth_images_unused, every.depth_images);
  std::printf("depth images: %llu rendered, %llu not rendered (every image: %llu rendered)\n",
              static_cast<unsigned long long>(lazy.depth_images),
              static_cast<unsigned long long>(lazy.depth_images_unused),
              static_cast<unsigned long long>(every.depth_images));
}
