// The footstep replay recorder on nao_stairs: a frame per step decision, the plan, the feet the
// run took, the navigator's heightmap filling in, and the page's JSON footstep layer.
#include "bipednav/runner/footstep_replay.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "test_data.hpp"

using namespace bipednav;

namespace {

std::size_t unobserved(const viz::ReplayGrid& g) { return std::count(g.cells.begin(), g.cells.end(), 255); }

}  // namespace

TEST(FootstepReplay, RecordsTheStairsRun) {
  const auto s = sim::load_scenario(test::source_dir() / "scenarios" / "nao_stairs.yaml");
  runner::FootstepReplayRecorder recorder(s);
  runner::FootstepRunOptions o;
  recorder.attach(o);
  const runner::FootstepRunResult run = runner::run_footstep_scenario(s, o);
  ASSERT_TRUE(run.summary.success);
  const viz::ReplayData d = recorder.finish(run);

  // One frame per decision: before every step and the final one.
  const auto& frames = d.frames;
  ASSERT_EQ(frames.size(), run.steps.size() + 1);
  for (std::size_t i = 1; i < frames.size(); ++i) {
    EXPECT_GT(frames[i].t_s, frames[i - 1].t_s);
    EXPECT_NEAR(frames[i].true_pose.x, run.steps[i - 1].body.x, 1e-9);
  }
  EXPECT_NEAR(frames.front().true_pose.x, s.start.x, 0.05);
  EXPECT_EQ(frames.back().state, "SUCCEEDED");
  EXPECT_EQ(frames.back().outcome, "SUCCESS");
  EXPECT_TRUE(frames.back().plan.empty());
  ASSERT_FALSE(frames.front().plan.empty());  // the first plan, to the goal
  EXPECT_NEAR(frames.front().plan.back().pose.x, s.goals.back().pose.x, 0.2);
  EXPECT_TRUE(frames.front().replanned);
  std::size_t replans = 0;
  for (const auto& f : frames) replans += f.replanned;
  EXPECT_EQ(replans, run.summary.replans + 1);  // every plan, the first included
  EXPECT_LT(distance(frames.back().estimated_pose, frames.back().true_pose), 0.1);

  // The feet taken: the start feet, then one per step, with the kinds of their actions.
  ASSERT_TRUE(d.footsteps.has_value());
  const viz::ReplayFootsteps& fs = *d.footsteps;
  ASSERT_EQ(fs.taken.size(), run.steps.size() + 2);
  EXPECT_EQ(fs.taken[2].action, frames[0].active_node);
  const auto kinds = [&](const std::string& k) {
    return std::count_if(fs.taken.begin(), fs.taken.end(), [&](const viz::ReplayFoot& f) { return f.action == k; });
  };
  EXPECT_GE(kinds("step_onto"), 2);
  EXPECT_GE(kinds("step_down"), 2);
  EXPECT_GT(kinds("planar"), 5);
  EXPECT_DOUBLE_EQ(fs.foot_length_m, run.body.foot_length_m);

  // The heightmap fills in as the robot looks around and walks; its range covers the platform.
  ASSERT_GE(fs.height_maps.size(), 3u);
  EXPECT_LT(unobserved(fs.height_maps.back()), unobserved(fs.height_maps.front()));
  EXPECT_LE(fs.height_lo_m, 0.0);
  EXPECT_GE(fs.height_hi_m, 0.1);

  // The page's JSON carries the layer; a few hundred kB at most.
  const std::string html = viz::replay_html(d);
  EXPECT_LT(html.size(), 1'000'000u);
  const auto j = nlohmann::json::parse(viz::replay_json(d));
  EXPECT_EQ(j["footsteps"]["taken"].size(), run.steps.size() + 2);
  EXPECT_EQ(j["height_maps"].size(), fs.height_maps.size());
  EXPECT_TRUE(j["frames"][0].contains("plan"));
}
