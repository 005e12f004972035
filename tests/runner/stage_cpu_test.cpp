// The per-stage CPU accounting of a closed-loop run (values only, no timing thresholds).
#include <gtest/gtest.h>

#include "bipednav/runner/scenario_runner.hpp"
#include "test_data.hpp"

using namespace bipednav;

TEST(StageCpu, EveryStageIsReportedAndTheyAddUpToAtMostTheRunsCpu) {
  const sim::Scenario s = sim::load_scenario(test::source_dir() / "scenarios" / "hexagon_static.yaml");
  runner::RunOptions o;
  o.time_limit_s = 2.0;
  const runner::RunResult r = runner::run_scenario(s, o);
  EXPECT_NEAR(r.time_s, 2.0, 0.011);
  ASSERT_GT(r.cpu_s, 0.0);
  EXPECT_NEAR(r.cpu_real_time_factor, r.time_s / r.cpu_s, 1e-9);
  double sum_ms = 0.0;
  for (const char* name : {"setup", "sim_lidar", "sim_depth", "sim_rest", "sensor_gate", "localization", "perception",
                           "local_map", "global_map", "global_planner", "local_planner", "control", "runner"}) {
    ASSERT_TRUE(r.stage_cpu_ms.contains(name)) << name;
    EXPECT_GE(r.stage_cpu_ms.at(name), 0.0) << name;
    sum_ms += r.stage_cpu_ms.at(name);
  }
  EXPECT_EQ(r.stage_cpu_ms.size(), 13u);
  EXPECT_LE(sum_ms, r.cpu_s * 1000.0 + 1e-6);
  // The sensors rendered and the pipeline ran: those stages took some CPU.
  for (const char* name : {"sim_lidar", "sim_depth", "perception", "localization"})
    EXPECT_GT(r.stage_cpu_ms.at(name), 0.0) << name;
}
