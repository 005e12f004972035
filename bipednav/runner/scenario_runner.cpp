#include "bipednav/runner/scenario_runner.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/cpu_time.hpp"
#include "bipednav/common/progress.hpp"
#include "bipednav/navigation/robot_loading.hpp"

namespace bipednav::runner {

navigation::MapArea map_area_for(const sim::Scenario& s, double margin_m) {
  return {s.bounds.min_x_m, s.bounds.min_y_m, s.bounds.max_x_m, s.bounds.max_y_m, margin_m};
}

mapping::GridGeometry global_geometry_for(const sim::Scenario& s, double res, double margin_m) {
  return navigation::global_grid_for(map_area_for(s, margin_m), res);
}

navigation::NavigatorParams navigator_params(const RobotProfile& robot, const RunOptions& o) {
  auto p = navigation::navigator_params_for(robot, o.params_file);
  if (!o.localization.empty()) p.localization.method = o.localization;
  if (!o.local_planner.empty()) p.server.local_planner = o.local_planner;
  if (!o.global_planner.empty()) p.server.global_planner = o.global_planner;
  return p;
}

// Called every step: each pose's search starts at the old pose that was near its predecessor and stops at
// the first near one, so an unchanged or locally changed path costs about one distance per pose, not all
// pairs (which took 11-14 % of a three_rooms run's CPU).
bool path_departs(const Path& before, const Path& after, double limit_m) {
  if (before.empty() || after.empty()) return !after.empty();
  const std::size_t n = before.size();
  std::size_t hint = 0;
  for (const auto& p : after.poses) {
    std::size_t k = 0;
    while (k < n && !(distance(p, before.poses[(hint + k) % n]) <= limit_m)) ++k;
    if (k == n) return true;
    hint = (hint + k) % n;
  }
  return false;
}

namespace {

// navigator_params with the scenario's goal tolerances.
navigation::NavigatorParams scenario_navigator_params(const sim::Scenario& scenario, const RobotProfile& robot,
                                                      const RunOptions& o) {
  auto params = navigator_params(robot, o);
  params.server.goal.xy_tolerance_m = scenario.goal_tolerance_m;
  params.server.goal.yaw_tolerance_rad = scenario.goal_tolerance_rad;
  return params;
}

Snapshot snapshot(double t, const navigation::Navigator& nav, const sim::Simulation& sim) {
  return {t,
          sim.true_pose(),
          nav.global_map().costmap(),
          nav.local_map().costmap(),
          nav.global_path(),
          nav.local_trajectory(),
          sim.actor_poses()};
}

// What run_scenario keeps of the loop after each step: the travelled path, the periodic trace and
// the snapshots at replanning moments.
struct StepRecorder {
  const RunOptions& o;
  Pose2 last;
  Path last_path;
  std::uint64_t last_path_version = 0;  // the navigator's global path version last compared
  double next_trace = 0.0;

  // Returns true when it took a periodic trace sample.
  bool record(const sim::Simulation& sim, const navigation::Navigator& nav, const Twist& cmd, RunResult& out) {
    out.path_length_m += distance(last, sim.true_pose());
    last = sim.true_pose();
    bool sampled = false;
    if (sim.now_s() + 1e-9 >= next_trace) {
      next_trace += o.trace_period_s;
      out.trace.push_back({sim.now_s(), sim.true_pose(), nav.pose(), cmd, nav.status().active_leaf, sim.actor_poses()});
      sampled = true;
    }
    // An unchanged path compares as it did last time (not departed: a departed path becomes last_path).
    if (nav.global_path_version() != last_path_version) {
      last_path_version = nav.global_path_version();
      if (path_departs(last_path, nav.global_path())) {
        const bool spaced = out.snapshots.empty() || sim.now_s() - out.snapshots.back().t_s >= o.snapshot_spacing_s;
        if (out.snapshots.size() < o.max_snapshots && !last_path.empty() && spaced)
          out.snapshots.push_back(snapshot(sim.now_s(), nav, sim));
        last_path = nav.global_path();
      }
    }
    return sampled;
  }
  // The trace ends with the final step (the robot's last command), not the last periodic sample.
  void finish(const sim::Simulation& sim, const navigation::Navigator& nav, const Twist& cmd, RunResult& out) const {
    if (out.trace.empty() || out.trace.back().t_s + 1e-9 < sim.now_s())
      out.trace.push_back({sim.now_s(), sim.true_pose(), nav.pose(), cmd, nav.status().active_leaf, sim.actor_poses()});
  }
};

// The navigator's command on its way to the simulated robot: the link (which a command_dropout
// fault cuts) and the walking controller's watchdog in front of the robot model.
class CommandLink {
 public:
  explicit CommandLink(const control::StopOnSilenceParams& params) : watchdog_(gait_, params) {}
  CommandLink(const CommandLink&) = delete;
  CommandLink& operator=(const CommandLink&) = delete;

  void send(const Twist& cmd, double stamp_s, sim::FaultInjector& faults) {
    if (!faults.drops_command(stamp_s)) watchdog_.send(cmd, stamp_s);
  }
  // The command the robot model executes during the step of step_s from now_s.
  const Twist& to_robot(double now_s, double step_s) {
    const bool was_stopped = watchdog_.stopped();
    if (watchdog_.tick(now_s)) {
      stops_ += was_stopped ? 0 : 1;
      stopped_s_ += step_s;
    }
    return gait_.last();
  }
  std::size_t stops() const { return stops_; }
  double stopped_s() const { return stopped_s_; }

 private:
  control::GaitCommandBuffer gait_;
  control::StopOnSilence watchdog_;
  std::size_t stops_ = 0;
  double stopped_s_ = 0.0;
};

// Simulated, wall and process CPU time of the run, and their ratios (the real-time factors).
void record_times(RunResult& out, double time_s, double wall_ms, double cpu_start_ms, double cpu_end_ms) {
  out.wall_s = wall_ms / 1000.0;
  out.time_s = time_s;
  out.real_time_factor = out.wall_s > 0 ? out.time_s / out.wall_s : 0.0;
  out.cpu_s = (cpu_end_ms - cpu_start_ms) / 1000.0;
  out.cpu_real_time_factor = out.cpu_s > 0 ? out.time_s / out.cpu_s : 0.0;
}

// Process CPU per stage (RunResult::stage_cpu_ms) from the simulator's and the navigator's
// counters and the runner's clock readings: the run's start, the loop's start and end, and the
// CPU spent inside Simulation::step.
void record_stage_cpu(RunResult& out, const sim::Simulation& sim, const navigation::Navigator& nav, double cpu_start_ms,
                      double cpu_loop_ms, double cpu_end_ms, double sim_ms) {
  const sim::SimulationStats& ss = sim.stats();
  const navigation::NavigatorCpu& nc = nav.cpu();
  auto& st = out.stage_cpu_ms;
  st["setup"] = cpu_loop_ms - cpu_start_ms;
  st["sim_lidar"] = ss.lidar_cpu_ms;
  st["sim_depth"] = ss.depth_cpu_ms;
  st["sim_rest"] = std::max(0.0, sim_ms - ss.lidar_cpu_ms - ss.depth_cpu_ms);
  st["sensor_gate"] = nc.sensor_gate_ms;
  st["localization"] = nc.localization_ms;
  st["perception"] = nc.perception_ms;
  st["local_map"] = nc.local_map_ms;
  st["global_map"] = nc.global_map_ms;
  st["global_planner"] = nc.global_planner_ms;
  st["local_planner"] = nc.local_planner_ms;
  st["control"] =
      std::max(0.0, nc.control_ms - nc.global_planner_ms - nc.local_planner_ms);  // tree, checks, recoveries
  // Navigator time outside its stages (building the perception input) goes with the runner.
  st["runner"] = std::max(0.0, (cpu_end_ms - cpu_loop_ms) - sim_ms - nc.total_ms());
}

std::string fixed(double v, int digits) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

}  // namespace

void judge_run(RunResult& r, double goal_tolerance_m, double goal_tolerance_rad) {
  const bool reported = r.outcome.ok();
  const bool inside = r.goal_error_m <= goal_tolerance_m && r.goal_error_rad <= goal_tolerance_rad;
  r.success = reported && r.collisions == 0 && inside;
  std::string why;
  if (r.first_collision) {
    const sim::CollisionEvent& c = *r.first_collision;
    why = "the robot touched " + c.obstacle + " at t = " + fixed(c.time_s, 1) + " s" +
          (sim::robot_standing(c) ? " while standing still" : "");
  }
  if (!inside && reported)
    why += (why.empty() ? "" : "; ") + std::string("the true pose is ") + fixed(r.goal_error_m, 2) + " m / " +
           fixed(r.goal_error_rad, 2) + " rad from the goal";
  if (!reported) {
    const std::string navigator =
        std::string(outcome_name(r.outcome.outcome)) + (r.outcome.message.empty() ? "" : ": " + r.outcome.message);
    r.verdict = why.empty() ? navigator : navigator + "; " + why;
  } else {
    r.verdict = why.empty() ? "" : "navigator reported SUCCESS, but " + why;
  }
}

namespace {

// The run's outcome: collisions, clearance, the navigator's counts and result, the true goal error
// and success (see run_scenario).
void record_outcome(RunResult& out, const sim::Scenario& scenario, const sim::Simulation& sim,
                    const navigation::Navigator& nav, double time_limit_s) {
  out.first_collision = sim.first_collision();
  out.contacts = sim.contacts();
  out.collisions = static_cast<int>(out.contacts.size());
  out.min_clearance_m = sim.min_clearance_m();
  out.replans = nav.replans();
  out.recoveries = nav.recoveries();
  out.recovery_log = nav.recovery_log();
  out.final_state = snapshot(sim.now_s(), nav, sim);
  out.localization_error_m = distance(nav.pose(), sim.true_pose());
  const auto& status = nav.status();
  const bool stopped_at_contact = out.first_collision && sim.now_s() < time_limit_s;
  out.outcome = status.state != navigation::NavState::ACTIVE ? status.result
                : stopped_at_contact ? Result{Outcome::CTRL_CANCELED, "run stopped at the first contact"}
                                     : Result{Outcome::CTRL_PAT_EXCEEDED, "time limit reached before the goal"};
  if (!scenario.goals.empty()) {
    const Pose2 goal = scenario.goals.back().pose;
    out.goal_error_m = distance(goal, sim.true_pose());
    out.goal_error_rad = std::abs(angle_diff(goal.theta, sim.true_pose().theta));
  }
  out.final_true_pose = sim.true_pose();
  out.final_estimated_pose = nav.pose();
  judge_run(out, scenario.goal_tolerance_m, scenario.goal_tolerance_rad);
}

}  // namespace

RunResult run_scenario(const sim::Scenario& scenario, const RunOptions& o) {
  const double cpu_start_ms = process_cpu_ms();
  RunResult out;
  out.scenario = scenario.name;
  out.seed = o.seed.value_or(scenario.seed);
  const RobotProfile robot = navigation::load_robot(o.robot.empty() ? scenario.robot : o.robot, o.config_dir);
  out.robot = robot.name;
  sim::SimulationParams sp;
  sp.seed = o.seed.value_or(scenario.seed);
  sim::Simulation sim(scenario.world, robot, scenario.start, sp);
  const auto params = scenario_navigator_params(scenario, robot, o);
  navigation::Navigator nav(params, robot, global_geometry_for(scenario, params.global_map.resolution_m),
                            scenario.start);
  const double limit = o.time_limit_s.value_or(scenario.time_limit_s);
  std::vector<sim::Fault> faults = scenario.faults;
  faults.insert(faults.end(), o.faults.begin(), o.faults.end());
  sim::FaultInjector injector(faults, sp.seed);
  // Without sensor faults the navigator may decline depth images before they are rendered.
  const bool sensor_faults = injector.has_sensor_faults();
  if (!sensor_faults && !o.render_unused_depth && params.newest_depth_only)
    sim.set_depth_demand([&nav](const std::string& camera, double capture_s, double stamp_s, bool newer_in_step) {
      return nav.wants_depth(camera, capture_s, stamp_s, newer_in_step);
    });
  const std::vector<sim::TimedGoal> goals = sim::goals_with_floods(scenario.goals, faults, scenario.bounds, sp.seed);
  std::size_t next_goal = 0;
  Twist cmd;
  CommandLink link(o.command_watchdog);
  StepRecorder recorder{o, sim.true_pose(), {}};
  Stopwatch wall;
  const double cpu_loop_ms = process_cpu_ms();
  double sim_ms = 0.0;
  ProgressBar bar("simulating " + scenario.name, static_cast<std::size_t>(limit * 10), o.progress);
  while (sim.now_s() < limit) {
    for (; next_goal < goals.size() && goals[next_goal].time_s <= sim.now_s(); ++next_goal) {
      ++out.goals_given;
      nav.set_goal(goals[next_goal].pose);
    }
    const double t0_ms = process_cpu_ms();
    const Twist& to_robot = link.to_robot(sim.now_s(), sim.params().step_s);
    SensorFrame frame = sensor_faults ? injector.apply(sim.step(to_robot)) : sim.step(to_robot);
    const double t1_ms = process_cpu_ms();
    cmd = nav.tick(frame);
    link.send(cmd, sim.now_s(), injector);
    sim_ms += t1_ms - t0_ms;
    if (o.on_step) o.on_step(sim, frame, nav, cmd);
    if (!out.first_arrival_s && next_goal == goals.size() && !goals.empty() &&
        distance(sim.true_pose(), goals.back().pose) <= scenario.goal_tolerance_m &&
        std::abs(angle_diff(goals.back().pose.theta, sim.true_pose().theta)) <= scenario.goal_tolerance_rad)
      out.first_arrival_s = sim.now_s();
    if (recorder.record(sim, nav, cmd, out)) bar.update(static_cast<std::size_t>(sim.now_s() * 10));
    sim.recycle(std::move(frame));  // its clouds' buffers hold the next frames' clouds
    if (o.stop_on_contact && sim.first_collision()) break;
    const bool more_goals = next_goal < goals.size();
    const auto state = nav.status().state;
    if (!more_goals && (state == navigation::NavState::SUCCEEDED || state == navigation::NavState::FAILED)) break;
  }
  recorder.finish(sim, nav, cmd, out);
  bar.finish();
  const double wall_ms = wall.elapsed_ms(), cpu_end_ms = process_cpu_ms();
  record_times(out, sim.now_s(), wall_ms, cpu_start_ms, cpu_end_ms);
  out.depth_images = sim.stats().depth_images;
  out.depth_images_unused = nav.depth_frames_skipped();
  record_stage_cpu(out, sim, nav, cpu_start_ms, cpu_loop_ms, cpu_end_ms, sim_ms);
  out.faults = injector.counters();
  out.watchdog_stops = link.stops();
  out.watchdog_stopped_s = link.stopped_s();
  record_outcome(out, scenario, sim, nav, limit);
  return out;
}

}  // namespace bipednav::runner
