#include "bench/local.hpp"

#include "bench/local_scene.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/planning/local/teb_params.hpp"
#include "bipednav/runner/scenario_runner.hpp"

namespace bipednav::bench {

nlohmann::json run_local_bench(const LocalBenchOptions& a) {
  using planning::local::TebParams;
  TebParams base;
  const std::string robot_name = a.robot.empty() && !a.params.empty() ? "turtlebot3" : a.robot;
  if (!robot_name.empty()) {
    const RobotProfile robot = navigation::load_robot(robot_name);
    if (robot.kind == "humanoid")
      throw Error("bench local --robot " + robot_name + ": a humanoid walks by footsteps, no TEB");
    runner::RunOptions o;
    o.params_file = a.params;
    base = runner::navigator_params(robot, o).server.local.teb;
  }
  nlohmann::json j;
  j["benchmark"] = "local";
  j["threads"] = a.threads;
  j["teb_settings"] = robot_name.empty() ? "TebParams defaults" : "robot " + robot_name;
  if (!robot_name.empty()) j["robot"] = robot_name;
  if (!a.params.empty()) j["params"] = a.params;
  j["homotopy_classes"] = true;
  j["goal_median_ms"] = 10.0;
  j["goal_p99_ms"] = 25.0;
  j["timing"] = "the goals on thread CPU time (cpu_*); *_ms without cpu are wall time";
  for (const int n : {0, 20, 100}) {
    TebParams params = base;
    params.homotopy.enabled = true;
    params.homotopy.num_threads = a.threads;
    const auto st = run_local_bench(make_local_bench_scene(n, 42), params, a.cycles);
    nlohmann::json e;
    e["obstacles_placed"] = n;
    e["obstacles_extracted"] = st.obstacles;
    e["cycles"] = st.cycles;
    e["success_cycles"] = st.success_cycles;
    e["median_ms"] = st.median_ms;
    e["p99_ms"] = st.p99_ms;
    e["max_ms"] = st.max_ms;
    e["cpu_median_ms"] = st.cpu_median_ms;
    e["cpu_p99_ms"] = st.cpu_p99_ms;
    j["per_obstacle_count"].push_back(e);
    if (n == 100) {
      j["median_ms"] = st.median_ms;
      j["p99_ms"] = st.p99_ms;
      j["cpu_median_ms"] = st.cpu_median_ms;
      j["cpu_p99_ms"] = st.cpu_p99_ms;
      // The goals are on one core: the calling thread's CPU time, which another process's load does
      // not inflate as it does the wall time.
      j["meets_goal_median"] = st.cpu_median_ms <= 10.0;
      j["meets_goal_p99"] = st.cpu_p99_ms <= 25.0;
    }
  }
  return j;
}

}  // namespace bipednav::bench
