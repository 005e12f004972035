#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/control/gait_command.hpp"
#include "bipednav/navigation/map_area.hpp"
#include "bipednav/navigation/navigator.hpp"
#include "bipednav/sim/fault_injection.hpp"
#include "bipednav/sim/scenario.hpp"
#include "bipednav/sim/simulation.hpp"

namespace bipednav::runner {

struct RunOptions {
  std::string robot;                   // overrides the scenario's robot profile (empty: keep)
  std::optional<std::uint64_t> seed;   // overrides the scenario's seed
  std::optional<double> time_limit_s;  // overrides the scenario's time limit
  std::string localization;            // loam | odometry (empty: the navigator's default)
  std::string local_planner;           // teb | tracker (empty: default)
  std::string global_planner;          // dstar_lite | astar (empty: default)
  std::filesystem::path config_dir;    // robot profiles (empty: the compiled-in config/)
  double trace_period_s = 0.1;         // how often the run is recorded for figures
  bool progress = false;               // progress bar on stderr
  std::size_t max_snapshots = 3;       // figure panels at replanning moments
  double snapshot_spacing_s = 5.0;     // ... at least this far apart
  std::vector<sim::Fault> faults;      // injected in addition to the scenario's own
  // End the run at the first contact, its verdict known (benchmarks); the navigator's outcome is then
  // CTRL_CANCELED unless it had finished.
  bool stop_on_contact = false;
  // The walking controller's watchdog: the navigator's command reaches the simulated robot through
  // control::StopOnSilence, as on the robot and in the ROS simulator node, so a lost command link
  // (fault command_dropout) stops the robot after timeout_s.
  control::StopOnSilenceParams command_watchdog;
  // A navigation parameters file (navigator_params_yaml.hpp) overlaid on the robot's defaults before
  // localization, local_planner and global_planner (empty: none). The scenario's goal tolerances win.
  std::filesystem::path params_file;
  // Render every depth image, also those the navigator would drop unseen (newest_depth_only). By
  // default the simulator asks the navigator first (Simulation::set_depth_demand with
  // Navigator::wants_depth; runs with injected faults render every image): the run is the same
  // bit for bit, for a third less depth rendering at 15 Hz against the 10 Hz map. A recorder that
  // should see every image (the rosbag) sets it.
  bool render_unused_depth = false;
  // Called after every step with the simulator, its sensor frame, the navigator and the command
  // (e.g. a rosbag recorder).
  std::function<void(const sim::Simulation&, const SensorFrame&, const navigation::Navigator&, const Twist&)> on_step;
};

// A recorded moment of the run (for the figure, the replay and the summary).
struct TraceSample {
  double t_s = 0.0;
  Pose2 true_pose, estimated_pose;
  Twist cmd;  // the navigator's (under a command_dropout fault the robot's watchdog may have stopped it)
  std::string active_leaf;
  std::vector<SE3> actors;
};

// The state of the maps and plans at a replanning moment (a figure panel).
struct Snapshot {
  double t_s = 0.0;
  Pose2 pose;
  mapping::Costmap2D global_costmap, local_costmap;
  Path global_path, local_trajectory;
  std::vector<SE3> actors;
};

struct RunResult {
  std::string scenario, robot;
  std::uint64_t seed = 0;  // the simulator's
  // The run's verdict (run_scenario): the navigator reported SUCCESS, the true pose ended within the
  // scenario's goal tolerances, and nothing was touched.
  bool success = false;
  // Why the run failed, in words ("navigator reported SUCCESS, but the robot touched wall_3 at
  // t = 12.4 s"; "true pose 0.61 m from the goal"); empty on success.
  std::string verdict;
  Result outcome;      // the navigator's
  int collisions = 0;  // contacts: the size of `contacts` (run_scenario), of the walker's (footstep runs)
  std::optional<sim::CollisionEvent> first_collision;
  // Every contact of the run, oldest first (sim::Simulation::contacts); run_scenario fills it, the
  // footstep runs keep theirs in FootstepRunOutput::contacts.
  std::vector<sim::CollisionEvent> contacts;
  double time_s = 0.0;
  Pose2 final_true_pose, final_estimated_pose;
  // The first time the true pose was within the last goal's tolerances (once every goal was given).
  std::optional<double> first_arrival_s;
  double path_length_m = 0.0;
  double min_clearance_m = 0.0;
  double goal_error_m = 0.0, goal_error_rad = 0.0;
  double localization_error_m = 0.0;  // estimated vs true pose at the end
  std::size_t replans = 0, recoveries = 0;
  // The latest recoveries with their MBF outcomes (Navigator::recovery_log), oldest first.
  std::vector<navigation::RecoveryRecord> recovery_log;
  double real_time_factor = 0.0, wall_s = 0.0;  // simulated time / wall time (says little on a shared machine)
  // Process CPU time of the run (setup and loop; not the figure) and simulated time / cpu_s.
  double cpu_s = 0.0, cpu_real_time_factor = 0.0;
  // Process CPU per stage in ms, summing to at most cpu_s: setup (world, sensors, navigator),
  // sim_lidar, sim_depth, sim_rest (robot, odometry, collisions, fault injection), sensor_gate,
  // localization, perception (with the split into observations), local_map, global_map,
  // control (behavior tree, D* Lite, TEB) and runner (recording the run).
  std::map<std::string, double> stage_cpu_ms;
  std::size_t goals_given = 0;
  // Depth images rendered, and those the navigator declined before rendering (RunOptions::
  // render_unused_depth off) or dropped after (on, or with faults).
  std::uint64_t depth_images = 0, depth_images_unused = 0;
  sim::FaultCounters faults;  // what the fault injector did
  // How often the walking controller's watchdog stopped the robot for want of commands, and the
  // simulated time it held it stopped.
  std::size_t watchdog_stops = 0;
  double watchdog_stopped_s = 0.0;
  std::vector<TraceSample> trace;
  std::vector<Snapshot> snapshots;
  Snapshot final_state;
};

// The area a navigator's global map covers for `scenario`: its bounds plus `margin_m` on every side.
navigation::MapArea map_area_for(const sim::Scenario& scenario, double margin_m = 2.0);
// The global map's grid: the scenario's bounds plus a margin, at the given resolution.
mapping::GridGeometry global_geometry_for(const sim::Scenario& scenario, double resolution_m, double margin_m = 2.0);

// Whether `after` leaves `before` by more than `limit_m` somewhere: some pose of it is farther than
// that from every pose of `before` (a replan worth a figure panel). An empty `after` never does; a
// non-empty one leaves an empty `before`.
bool path_departs(const Path& before, const Path& after, double limit_m = 0.5);

// Runs a scenario closed-loop: the simulator's sensor frames feed the Navigator (through the
// fault injector when the scenario or the options name faults), its command drives the simulated robot
// (through the walking controller's watchdog, RunOptions::command_watchdog); goals are
// handed over at their times; the run ends when the last goal succeeded or failed, or at the time limit. Success = the
// navigator reported the last goal reached, the true pose ends within the scenario's tolerances
// (the controllers aim inside them, ServerParams::controller_goal_tolerance_fraction, to leave room
// for the localization error) and nothing was touched.
RunResult run_scenario(const sim::Scenario& scenario, const RunOptions& options);
// That rule: sets r.success and r.verdict (why a run failed, in words) from the navigator's outcome,
// the first contact and the true goal error against the tolerances. The footstep runs use it too.
void judge_run(RunResult& r, double goal_tolerance_m, double goal_tolerance_rad);
// The navigator's parameters for a run of `robot`: its defaults, options.params_file
// (navigation::navigator_params_for), then the localization / planner options (without the
// scenario's goal tolerances).
navigation::NavigatorParams navigator_params(const RobotProfile& robot, const RunOptions& options);

}  // namespace bipednav::runner
