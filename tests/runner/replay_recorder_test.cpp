// The replay recorder on a short closed-loop run: frames at its period, maps only when changed,
// points in the world frame, and a page the writer accepts.
#include "bipednav/runner/replay_recorder.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_data.hpp"

using namespace bipednav;

namespace {

struct Recorded {
  sim::Scenario scenario;
  runner::RunResult result;
  viz::ReplayData data;
};

Recorded record_hexagon(double seconds) {
  Recorded r;
  r.scenario = sim::load_scenario(test::source_dir() / "scenarios" / "hexagon_static.yaml");
  runner::ReplayRecorder recorder(r.scenario);
  runner::RunOptions o;
  o.time_limit_s = seconds;
  recorder.attach(o);
  r.result = runner::run_scenario(r.scenario, o);
  r.data = recorder.finish(r.result);
  return r;
}

}  // namespace

TEST(ReplayRecorder, RecordsAShortRun) {
  const Recorded r = record_hexagon(4.0);
  const auto& frames = r.data.frames;
  ASSERT_GE(frames.size(), 38u);  // every 0.1 s, plus navigation-state and active-node changes
  ASSERT_LE(frames.size(), 60u);
  EXPECT_NEAR(frames.front().true_pose.x, r.scenario.start.x, 0.05);
  EXPECT_GT(frames.back().true_pose.x, frames.front().true_pose.x + 0.2);  // it drove towards the goal
  for (std::size_t i = 1; i < frames.size(); ++i) EXPECT_GT(frames[i].t_s, frames[i - 1].t_s);
  EXPECT_EQ(frames.back().state, "ACTIVE");
  EXPECT_FALSE(frames.back().active_node.empty());
  EXPECT_FALSE(frames.back().global_path.empty());
  ASSERT_TRUE(frames.back().goal.has_value());
  EXPECT_NEAR(frames.back().goal->x, r.scenario.goals[0].pose.x, 1e-9);
  // LiDAR returns lie inside the hexagon (world frame, thinned) around the robot.
  ASSERT_FALSE(frames.back().lidar.empty());
  for (const auto& p : frames.back().lidar) EXPECT_LT(p.norm(), 4.0);
  // The global map is taken at most at 2 Hz and only when it changed; the local one at 5 Hz.
  EXPECT_GE(r.data.global_maps.size(), 1u);
  EXPECT_LE(r.data.global_maps.size(), 9u);
  EXPECT_GE(r.data.local_maps.size(), 5u);
  EXPECT_LE(r.data.local_maps.size(), 21u);
  EXPECT_FALSE(r.data.statics.empty());
  EXPECT_EQ(r.data.goals.size(), r.scenario.goals.size());
  EXPECT_DOUBLE_EQ(r.data.summary.time_s, r.result.time_s);
  EXPECT_GT(r.data.robot_radius_m, 0.1);
  EXPECT_NO_THROW(viz::replay_html(r.data));
}

TEST(ReplayRecorder, RejectsBadParameters) {
  const sim::Scenario s = sim::load_scenario(test::source_dir() / "scenarios" / "hexagon_static.yaml");
  runner::ReplayRecorderParams p;
  p.period_s = 0.0;
  EXPECT_THROW(runner::ReplayRecorder(s, p), ParamError);
  p = {};
  p.min_point_z_m = 3.0;
  EXPECT_THROW(runner::ReplayRecorder(s, p), ParamError);
}
