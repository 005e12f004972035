#include "bipednav/runner/replay_recorder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "bipednav/sim/world_drawing.hpp"

namespace bipednav::runner {

namespace {

constexpr double kPoseHistoryS = 0.5;  // longer than a LiDAR sweep

bool same_cells(const viz::ReplayGrid& a, const viz::ReplayGrid& b) {
  return a.width == b.width && a.height == b.height && a.origin_x_m == b.origin_x_m && a.origin_y_m == b.origin_y_m &&
         a.cells == b.cells;
}

// Appends the grid unless it equals the last one recorded.
void push_if_changed(std::vector<viz::ReplayGrid>& grids, viz::ReplayGrid grid) {
  if (!grids.empty() && same_cells(grids.back(), grid)) return;
  grids.push_back(std::move(grid));
}

}  // namespace

void ReplayRecorderParams::validate() const {
  require(std::isfinite(period_s) && period_s > 0.0, "period_s", "> 0 s");
  require(std::isfinite(global_map_period_s) && global_map_period_s > 0.0, "global_map_period_s", "> 0 s");
  require(std::isfinite(local_map_period_s) && local_map_period_s > 0.0, "local_map_period_s", "> 0 s");
  require(std::isfinite(points_period_s) && points_period_s > 0.0, "points_period_s", "> 0 s");
  require(std::isfinite(point_cell_m) && point_cell_m > 0.0, "point_cell_m", "> 0 m");
  require(std::isfinite(min_point_z_m) && std::isfinite(max_point_z_m) && min_point_z_m < max_point_z_m,
          "min_point_z_m/max_point_z_m", "finite with min < max");
}

viz::ReplayGrid replay_grid(double t_s, const mapping::Costmap2D& map) {
  const auto& g = map.geometry();
  return {t_s, g.width, g.height, g.resolution_m, g.origin_x_m, g.origin_y_m, map.data()};
}

viz::ReplayData replay_scene(const sim::Scenario& scenario) {
  viz::ReplayData data;
  data.title = scenario.name + (scenario.description.empty() ? "" : ": " + scenario.description);
  for (const auto& geometry : scenario.world.statics)
    for (auto& outline : sim::footprint(geometry, SE3::Identity())) data.statics.push_back(std::move(outline));
  for (const auto& actor : scenario.world.actors) {
    viz::ReplayActor a{actor.name, {}};
    for (const auto& part : actor.parts)
      for (auto& outline : sim::footprint(part, SE3::Identity())) a.outlines.push_back(std::move(outline));
    data.actors.push_back(std::move(a));
  }
  for (const auto& g : scenario.goals) data.goals.push_back({g.time_s, g.pose});
  return data;
}

viz::ReplaySummary replay_summary(const RunResult& r) {
  return {r.scenario,        r.robot,   r.success,       std::string(outcome_name(r.outcome.outcome)),
          r.outcome.message, r.time_s,  r.path_length_m, r.min_clearance_m,
          r.collisions,      r.replans, r.recoveries};
}

ReplayRecorder::ReplayRecorder(const sim::Scenario& scenario, const ReplayRecorderParams& params)
    : params_(params), data_(replay_scene(scenario)) {
  params_.validate();
}

void ReplayRecorder::attach(RunOptions& options) {
  auto previous = std::move(options.on_step);
  options.on_step = [this, previous](const sim::Simulation& sim, const SensorFrame& frame,
                                     const navigation::Navigator& nav, const Twist& cmd) {
    if (previous) previous(sim, frame, nav, cmd);
    record(sim, frame, nav, cmd);
  };
}

Pose2 ReplayRecorder::pose_at(double t_s) const {
  auto it = std::upper_bound(poses_.begin(), poses_.end(), t_s,
                             [](double t, const std::pair<double, Pose2>& p) { return t < p.first; });
  if (it == poses_.begin()) return poses_.front().second;
  return std::prev(it)->second;
}

// Points taken at their own time (a sweep's columns fire over 0.1 s while the robot moves), placed
// in the world by the true pose at that time, between min_point_z_m and max_point_z_m, one per cell.
std::vector<Eigen::Vector2f> ReplayRecorder::thin(const PointCloud& cloud, const SE3& T_base_sensor) const {
  std::vector<Eigen::Vector2f> out;
  std::unordered_set<std::int64_t> cells;
  float pose_offset_s = std::numeric_limits<float>::quiet_NaN();
  SE3 T_world_sensor = SE3::Identity();
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const float offset_s = cloud.has_time() ? cloud.time_offsets_s[i] : 0.0f;
    if (!(offset_s == pose_offset_s)) {
      pose_offset_s = offset_s;
      T_world_sensor = se3_from_pose2(pose_at(cloud.stamp_s + offset_s)) * T_base_sensor;
    }
    const Eigen::Vector3d w = T_world_sensor * cloud.points[i].cast<double>();
    if (!w.allFinite() || w.z() < params_.min_point_z_m || w.z() > params_.max_point_z_m) continue;
    const auto cx = static_cast<std::int64_t>(std::floor(w.x() / params_.point_cell_m));
    const auto cy = static_cast<std::int64_t>(std::floor(w.y() / params_.point_cell_m));
    if (!cells.insert(cx * 4000037 + cy).second) continue;
    out.emplace_back(static_cast<float>(w.x()), static_cast<float>(w.y()));
    if (out.size() >= params_.max_points) break;
  }
  return out;
}

bool ReplayRecorder::points_due(const std::string& sensor, double t_s) {
  auto [it, added] = next_points_s_.try_emplace(sensor, t_s);
  if (t_s + 1e-9 < it->second) return false;
  it->second = t_s + params_.points_period_s;
  return true;
}

void ReplayRecorder::take_points(const sim::Simulation& sim, const SensorFrame& frame) {
  const auto& robot = sim.robot();
  const double t = sim.now_s();
  poses_.emplace_back(t, sim.true_pose());
  while (poses_.front().first < t - kPoseHistoryS) poses_.pop_front();
  const SensorMount* lidar = frame.lidar ? robot.sensor(frame.lidar->frame_id) : nullptr;
  if (lidar && points_due(lidar->name, t)) lidar_ = thin(*frame.lidar, lidar->T_base_sensor());
  for (const auto& d : frame.depth) {
    const SensorMount* camera = robot.sensor(d.camera);
    if (camera && points_due(d.camera, t)) depth_[d.camera] = thin(d.cloud, camera->T_base_sensor());
  }
}

void ReplayRecorder::take_maps(double t_s, const navigation::Navigator& nav) {
  if (t_s + 1e-9 >= next_global_s_) {
    next_global_s_ = t_s + params_.global_map_period_s;
    push_if_changed(data_.global_maps, replay_grid(t_s, nav.global_map().costmap()));
  }
  if (t_s + 1e-9 >= next_local_s_) {
    next_local_s_ = t_s + params_.local_map_period_s;
    push_if_changed(data_.local_maps, replay_grid(t_s, nav.local_map().costmap()));
  }
}

void ReplayRecorder::record(const sim::Simulation& sim, const SensorFrame& frame, const navigation::Navigator& nav,
                            const Twist& cmd) {
  data_.robot_radius_m = sim.robot().footprint_radius_m;
  take_points(sim, frame);
  const double t = sim.now_s();
  const navigation::NavStatus& status = nav.status();
  const std::string state = navigation::nav_state_name(status.state);
  if (t + 1e-9 < next_frame_s_ && state == last_state_ && status.active_leaf == last_node_) return;
  next_frame_s_ = t + params_.period_s;
  last_state_ = state;
  last_node_ = status.active_leaf;
  take_maps(t, nav);
  viz::ReplayFrame f;
  f.t_s = t;
  f.true_pose = sim.true_pose();
  f.estimated_pose = nav.pose();
  f.cmd = cmd;
  f.goal = nav.goal();
  f.global_path = nav.global_path();
  f.local_trajectory = nav.local_trajectory();
  if (data_.local_planner.empty()) data_.local_planner = std::string(nav.server().local_planner().name());
  for (const SE3& T : sim.actor_poses()) f.actors.push_back(pose2_from_se3(T));
  f.lidar = lidar_;
  for (const auto& [camera, points] : depth_) f.depth.insert(f.depth.end(), points.begin(), points.end());
  f.active_node = status.active_leaf;
  f.state = state;
  if (status.state == navigation::NavState::SUCCEEDED || status.state == navigation::NavState::FAILED)
    f.outcome = std::string(outcome_name(status.result.outcome));
  data_.frames.push_back(std::move(f));
}

viz::ReplayData ReplayRecorder::finish(const RunResult& r) const {
  viz::ReplayData out = data_;
  out.summary = replay_summary(r);
  return out;
}

}  // namespace bipednav::runner
