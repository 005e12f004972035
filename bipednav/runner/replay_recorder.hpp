#pragma once

#include <deque>
#include <map>
#include <string>
#include <vector>

#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/viz/replay_html.hpp"

namespace bipednav::runner {

struct ReplayRecorderParams {
  double period_s = 0.1;             // frame sampling period (also on every navigation-state change)
  double global_map_period_s = 0.5;  // the global map's 2 Hz
  double local_map_period_s = 0.2;   // local map snapshots (it updates at 10 Hz)
  double points_period_s = 0.2;      // per sensor: the LiDAR sweeps at 10 Hz, depth at 15 Hz
  double point_cell_m = 0.05;        // LiDAR/depth points are thinned to one per 2D cell
  double min_point_z_m = 0.05;       // points above the ground ...
  double max_point_z_m = 2.0;        // ... and below this height (world frame)
  std::size_t max_points = 3000;     // per sensor and frame
  void validate() const;
};

// Records a closed-loop run for the HTML replay through RunOptions::on_step: robot poses, command,
// plans, actors, goals, the latest LiDAR and depth returns (projected to 2D in the world frame),
// the behavior tree's active node and the navigation state, and the costmaps when they change.
class ReplayRecorder {
 public:
  explicit ReplayRecorder(const sim::Scenario& scenario, const ReplayRecorderParams& params = {});

  // The per-step hook (RunOptions::on_step).
  void record(const sim::Simulation& sim, const SensorFrame& frame, const navigation::Navigator& nav, const Twist& cmd);
  // Installs record() as options.on_step (after any hook already there). The recorder must outlive the run.
  void attach(RunOptions& options);

  const std::vector<viz::ReplayFrame>& frames() const { return data_.frames; }
  // The recording with the run's summary.
  viz::ReplayData finish(const RunResult& result) const;

 private:
  void take_points(const sim::Simulation& sim, const SensorFrame& frame);
  bool points_due(const std::string& sensor, double t_s);
  void take_maps(double t_s, const navigation::Navigator& nav);
  std::vector<Eigen::Vector2f> thin(const PointCloud& cloud, const SE3& T_base_sensor) const;
  Pose2 pose_at(double t_s) const;  // the recorded true pose at or just before t_s

  ReplayRecorderParams params_;
  viz::ReplayData data_;
  std::deque<std::pair<double, Pose2>> poses_;                 // recent true poses, to place points
  std::vector<Eigen::Vector2f> lidar_;                         // the latest sweep
  std::map<std::string, std::vector<Eigen::Vector2f>> depth_;  // the latest cloud per camera
  std::map<std::string, double> next_points_s_;                // per sensor
  double next_frame_s_ = 0.0, next_global_s_ = 0.0, next_local_s_ = 0.0;
  std::string last_state_, last_node_;
};

// A replay's scene from the scenario: title, static outlines, actors and goals (no frames).
viz::ReplayData replay_scene(const sim::Scenario& scenario);
// The run's summary line.
viz::ReplaySummary replay_summary(const RunResult& result);

// The costmap as a replay grid (at time t_s).
viz::ReplayGrid replay_grid(double t_s, const mapping::Costmap2D& map);

}  // namespace bipednav::runner
