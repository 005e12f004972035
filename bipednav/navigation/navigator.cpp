#include "bipednav/navigation/navigator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/cpu_time.hpp"
#include "bipednav/planning/local/moving_obstacle_yield.hpp"
#include "bipednav/tracking/sensor_visibility.hpp"

namespace bipednav::navigation {
namespace {

// Parameters are checked before any stage is built from them, so a bad value is reported as the
// ParamError naming it (not as whatever a stage makes of it).
template <class Params>
Params validated(Params p) {
  p.validate();
  return p;
}

}  // namespace

std::string lidar_mount_name(const RobotProfile& robot) {
  const SensorMount* lidar = robot.lidar();
  return lidar ? lidar->name : std::string();
}

std::vector<std::string> depth_mount_names(const RobotProfile& robot) {
  std::vector<std::string> out;
  for (const auto& m : robot.sensors)
    if (m.type == "d430") out.push_back(m.name);
  return out;
}

const char* nav_state_name(NavState s) {
  switch (s) {
    case NavState::IDLE:
      return "IDLE";
    case NavState::ACTIVE:
      return "ACTIVE";
    case NavState::SUCCEEDED:
      return "SUCCEEDED";
    case NavState::FAILED:
      return "FAILED";
  }
  return "UNKNOWN";
}

Navigator::Navigator(NavigatorParams params, RobotProfile robot, const mapping::GridGeometry& global_geometry,
                     const Pose2& initial_pose)
    : params_(validated(std::move(params))),
      robot_(validated(std::move(robot))),
      perception_(params_.perception),
      localizer_(params_.localization, robot_, initial_pose),
      gate_(params_.sensors, lidar_mount_name(robot_), depth_mount_names(robot_)),
      local_(params_.local_map),
      global_(global_geometry, params_.global_map),
      moving_(params_.moving_obstacles),
      server_(params_.server, robot_, global_, local_, &moving_),
      tree_(bt::load_tree_xml(params_.behavior_tree, leaf_factory())),  // no leaf runs before the constructor ends
      local_gate_(params_.local_map.rate_hz),
      global_gate_(params_.global_map.rate_hz),
      control_gate_(params_.control_rate_hz) {
  lidar_name_ = lidar_mount_name(robot_);
  // Where the sensors see (for coasting tracks through their blind zone), with the ranges and the
  // obstacle height the perception pipeline keeps.
  tracking::SensorVisibilityParams visibility;
  visibility.depth_max_range_m = params_.perception.depth_max_range_m;
  visibility.lidar_min_range_m = params_.perception.lidar_min_range_m;
  visibility.lidar_max_range_m = params_.perception.lidar_max_range_m;
  visibility.min_obstacle_height_m = params_.perception.min_obstacle_height_m;
  moving_.set_visibility(tracking::SensorVisibility(robot_, visibility));
}

bt::Factory Navigator::leaf_factory() {
  bt::Factory factory;
  register_leaves(factory);
  return factory;
}

void Navigator::set_goal(const Pose2& goal) {
  goal_ = goal;
  tree_.blackboard()->set("goal", goal);
  server_.on_new_goal();
  if (status_.state != NavState::ACTIVE) {
    tree_.halt();
    status_ = {NavState::ACTIVE, {}, ""};
  }
}

void Navigator::cancel() {
  tree_.halt();
  server_.stop();
  cmd_ = {};
  goal_.reset();
  status_ = {NavState::IDLE, {Outcome::CTRL_CANCELED, "navigation canceled"}, ""};
}

Twist Navigator::tick(const SensorFrame& frame) {
  Admission admitted;
  {
    const CpuScope cpu(cpu_.sensor_gate_ms);
    admitted = gate_.check(frame);  // stale, out-of-order and NaN-only data dropped (no copies)
  }
  if (admitted.stamp_s < now_s_) return cmd_;  // a frame from the past changes nothing
  now_s_ = admitted.stamp_s;
  {
    const CpuScope cpu(cpu_.localization_ms);
    Stopwatch sw;
    if (admitted.odometry) localizer_.add_odometry(*frame.odometry);
    if (admitted.lidar) localizer_.add_sweep(*frame.lidar);
    timings_.localization_ms = sw.elapsed_ms();
  }
  perception_in_.stamp_s = admitted.stamp_s;
  perception_in_.lidar = admitted.lidar ? &*frame.lidar : nullptr;
  perception_in_.base_velocity = localizer_.velocity();
  perception_in_.depth.clear();
  for (std::size_t i = 0; i < frame.depth.size(); ++i) {
    if (!admitted.depth[i]) continue;
    if (!depth_judged_ahead_ && depth_superseded(frame, admitted, i))
      ++depth_frames_skipped_;
    else
      perception_in_.depth.push_back(&frame.depth[i]);
  }
  perceive(perception_in_);
  perception_in_.lidar = nullptr;  // the pointers are only valid during this tick
  perception_in_.depth.clear();
  update_maps();
  if (control_gate_.ready(now_s_)) {
    {
      const CpuScope cpu(cpu_.control_ms);
      control();
    }
    cpu_.global_planner_ms = server_.global_planner_cpu_ms();
    cpu_.local_planner_ms = server_.local_planner_cpu_ms();
  }
  return cmd_;
}

bool Navigator::depth_superseded(const SensorFrame& frame, const Admission& admitted, std::size_t i) {
  if (!params_.newest_depth_only) return false;
  const DepthCloud& d = frame.depth[i];
  bool newer_in_step = false;
  for (std::size_t j = i + 1; j < frame.depth.size() && !newer_in_step; ++j)
    newer_in_step = admitted.depth[j] && frame.depth[j].camera == d.camera;
  return depth_superseded(d.camera, d.cloud.stamp_s, now_s_, newer_in_step);
}

bool Navigator::depth_superseded(const std::string& camera, double stamp_s, double now_s, bool newer_in_step) {
  auto clock =
      std::find_if(depth_clocks_.begin(), depth_clocks_.end(), [&](const DepthClock& c) { return c.camera == camera; });
  double period = std::numeric_limits<double>::infinity();  // unknown before the camera's second frame
  if (clock == depth_clocks_.end()) {
    depth_clocks_.push_back({camera, stamp_s});
  } else {
    period = stamp_s - clock->last_stamp_s;
    clock->last_stamp_s = stamp_s;
  }
  if (newer_in_step) return true;            // a newer frame of the same camera supersedes it at once
  if (local_gate_.due(now_s)) return false;  // the map integrates this step's frames
  // The next frame arrives about one period from now (this frame's latency included): before the
  // next update, it replaces this one.
  return period > 0.0 && now_s + period < local_gate_.next_s() - 1e-9;
}

bool Navigator::wants_depth(const std::string& camera, double capture_s, double frame_stamp_s, bool newer_in_step) {
  depth_judged_ahead_ = true;
  if (!params_.newest_depth_only) return true;
  if (!depth_superseded(camera, capture_s, frame_stamp_s, newer_in_step)) return true;
  ++depth_frames_skipped_;
  return false;
}

namespace {

// Splits the base-frame points of one source into a map-frame observation.
mapping::Observation observation_for(const perception::SensorSource& src, const SE3& T_map_base, bool marking) {
  mapping::Observation o;
  o.origin_map = T_map_base * src.origin_base;
  o.max_range_m = src.max_range_m;
  o.marking = marking;
  o.clearing = true;
  return o;
}

void append_points(std::vector<mapping::Observation>& obs, const std::vector<perception::SensorSource>& sources,
                   const PointCloud& cloud, const std::vector<std::uint8_t>& source_of, const SE3& T_map_base,
                   bool marking, std::vector<std::vector<Eigen::Vector3f>>& spare, SourceRuns& work) {
  const std::size_t first = obs.size();
  for (const auto& s : sources) {
    obs.push_back(observation_for(s, T_map_base, marking));
    if (!spare.empty()) {  // a buffer of an earlier observation: no allocation (and page faults) again
      obs.back().points_map = std::move(spare.back());
      obs.back().points_map.clear();
      spare.pop_back();
    }
  }
  const Eigen::Matrix3f R = T_map_base.linear().cast<float>();
  const Eigen::Vector3f t = T_map_base.translation().cast<float>();
  // The cloud in runs of one source (each sensor's points are contiguous): each observation's
  // points counted, then written in place run by run (the same points in the same order as
  // appending them one by one, without a capacity test and a size update per point).
  std::vector<SourceRuns::Run>& runs = work.runs;
  std::vector<std::size_t>& fill = work.fill;
  runs.clear();
  const std::size_t n_src = obs.size() - first;
  fill.assign(n_src, 0);
  const auto src = [&](std::size_t i) -> std::size_t { return i < source_of.size() ? source_of[i] : 0; };
  for (std::size_t i = 0; i < cloud.size();) {
    const std::size_t k = src(i);
    std::size_t j = i + 1;
    while (j < cloud.size() && src(j) == k) ++j;
    if (k < n_src) runs.push_back({i, j, k}), fill[k] += j - i;
    i = j;
  }
  for (std::size_t k = 0; k < n_src; ++k) {
    std::vector<Eigen::Vector3f>& v = obs[first + k].points_map;
    const std::size_t old = v.size();
    v.resize(old + fill[k]);
    fill[k] = old;  // from here: the next slot to write
  }
  for (const SourceRuns::Run& r : runs) {
    Eigen::Vector3f* o = obs[first + r.k].points_map.data() + fill[r.k];
    for (std::size_t i = r.begin; i < r.end; ++i) *o++ = R * cloud.points[i] + t;
    fill[r.k] += r.end - r.begin;
  }
}

// Empties `obs`, keeping the point buffers in `spare`.
void recycle(std::vector<mapping::Observation>& obs, std::vector<std::vector<Eigen::Vector3f>>& spare) {
  for (auto& o : obs)
    if (o.points_map.capacity() > 0 && spare.size() < 64) spare.push_back(std::move(o.points_map));
  obs.clear();
}

}  // namespace

void Navigator::perceive(const perception::PerceptionInput& in) {
  if (!in.lidar && in.depth.empty()) return;
  const CpuScope cpu(cpu_.perception_ms);
  Stopwatch sw;
  perception_.process(in, robot_, perception_out_);
  timings_.perception_ms = sw.elapsed_ms();
  const SE3 T_map_base = se3_from_pose2(localizer_.T_map_base());
  // Obstacles mark and clear; ground returns only clear (so a moved obstacle leaves no trail).
  const std::size_t first = local_obs_.size();
  append_points(local_obs_, perception_out_.sources, perception_out_.obstacles, perception_out_.obstacle_source,
                T_map_base, true, spare_points_, source_runs_);
  if (in.lidar) {
    // The global map takes the LiDAR's obstacle observation of this frame, already in the map frame.
    recycle(lidar_obs_, spare_points_);
    for (std::size_t i = 0; i < perception_out_.sources.size(); ++i)
      if (perception_out_.sources[i].name == lidar_name_) lidar_obs_.push_back(local_obs_[first + i]);
  }
  append_points(local_obs_, perception_out_.sources, perception_out_.ground, perception_out_.ground_source, T_map_base,
                false, spare_points_, source_runs_);
}

void Navigator::update_maps() {
  const Pose2 pose = localizer_.T_map_base();
  if (local_gate_.ready(now_s_)) {
    const CpuScope cpu(cpu_.local_map_ms);
    Stopwatch sw;
    track_moving_obstacles();
    local_.update(pose, local_obs_);
    recycle(local_obs_, spare_points_);
    timings_.local_map_ms = sw.elapsed_ms();
  }
  if (global_gate_.ready(now_s_)) {
    const CpuScope cpu(cpu_.global_map_ms);
    Stopwatch sw;
    map_ready_ = map_ready_ || !lidar_obs_.empty() || now_s_ >= 1.0;
    server_.add_global_changes(global_.update(pose, lidar_obs_, &local_));
    recycle(lidar_obs_, spare_points_);
    timings_.global_map_ms = sw.elapsed_ms();
  }
}

Twist Navigator::yield_to_moving_obstacles(const Twist& cmd) const {
  // The local planners yield already; this catches the commands of the recoveries (backing up,
  // turning, waiting), which know nothing of moving obstacles. Never on stale perception: with a
  // sensor silent or localization unhealthy the tree's stop stands.
  if (!params_.moving_obstacles.enabled || !sensors_alive() || !localizer_.healthy(now_s_)) return cmd;
  const auto moving = moving_.moving(now_s_);
  if (moving.empty()) return cmd;
  return planning::local::yield_to_moving_obstacles(
             cmd, localizer_.T_map_base(), reference_velocity(), moving, local_.costmap(), server_.velocity_limits(),
             1.0 / params_.control_rate_hz, now_s_, params_.server.local.avoidance)
      .cmd;
}

Twist acceleration_reference(const Twist& measured, const Twist& last_command) {
  // While slowing down, the lagging measurement would undo the braking already commanded; while
  // speeding up it keeps the commands from running ahead of a robot that cannot follow.
  const auto pick = [](double commanded, double actual) {
    return std::abs(commanded) < std::abs(actual) ? commanded : actual;
  };
  Twist v = measured;
  v.linear_x = pick(last_command.linear_x, measured.linear_x);
  v.angular_z = pick(last_command.angular_z, measured.angular_z);
  return v;
}

Twist Navigator::reference_velocity() const {
  return params_.brake_from_last_command ? acceleration_reference(localizer_.velocity(), cmd_) : localizer_.velocity();
}

bool Navigator::sensors_alive() const { return gate_.all_alive(now_s_); }

void Navigator::control() {
  server_.set_view({now_s_, localizer_.T_map_base(), reference_velocity(), 1.0 / params_.control_rate_hz,
                    localizer_.weakest_position_sigma_m(), localizer_.velocity()});
  // Plans and goal checks wait for the first map built from the sensors.
  if (status_.state != NavState::ACTIVE || !map_ready_) {
    server_.stop();
    cmd_ = {};
    return;
  }
  Stopwatch sw;
  const bt::Status s = tree_.tick(now_s_);
  status_.active_leaf = tree_.active_leaf();
  if (auto p = tree_.blackboard()->get<Path>("path"); p && *p != global_path_) {
    global_path_ = std::move(*p);
    ++global_path_version_;
  }
  cmd_ = yield_to_moving_obstacles(server_.command());
  if (s == bt::Status::SUCCESS || s == bt::Status::FAILURE) finish(s);
  timings_.control_ms = sw.elapsed_ms();
}

std::string Navigator::weak_estimate_note() const {
  // The goal counts as reached on the estimate; where the estimate's 2-sigma reach exceeds the
  // tolerance (95 %), the true pose may well be outside it, and the result says so: along the
  // direction of travel to the goal first, else across it.
  const double tolerance_m = params_.server.goal.xy_tolerance_m;
  Eigen::Vector2d travel{1.0, 0.0};
  if (global_path_.poses.size() >= 2) {
    const Pose2& a = global_path_.poses.front();
    const Pose2& b = global_path_.poses.back();
    if (std::hypot(b.x - a.x, b.y - a.y) > 1e-6) travel = Eigen::Vector2d(b.x - a.x, b.y - a.y).normalized();
  }
  const Eigen::Vector2d across{-travel.y(), travel.x()};
  const double along_m = localizer_.position_sigma_m(travel), across_m = localizer_.position_sigma_m(across);
  if (2.0 * std::max(along_m, across_m) <= tolerance_m) return "";
  const bool along = 2.0 * along_m > tolerance_m;
  char buf[220];
  std::snprintf(buf, sizeof(buf),
                "; the position estimate is weak %s the direction of travel (sigma %.2f m, twice that exceeds the "
                "%.2f m tolerance): the LiDAR map did not observe it and odometry carried it",
                along ? "along" : "across", along ? along_m : across_m, tolerance_m);
  return buf;
}

void Navigator::finish(bt::Status s) {
  server_.stop();
  cmd_ = {};
  if (s == bt::Status::SUCCESS) {
    status_.state = NavState::SUCCEEDED;
    status_.result = {Outcome::SUCCESS, "goal reached" + weak_estimate_note()};
    return;
  }
  status_.state = NavState::FAILED;
  // The safety gate first: while sensors are silent or localization is unhealthy it halts the
  // navigation below it, so a failure now is the gate's, and error_code may still hold the code
  // of a controller failure the recoveries had overcome before.
  const int code = tree_.blackboard()->get<int>("error_code").value_or(0);
  if (!sensors_alive()) {
    std::string names;
    for (const auto& n : gate_.silent(now_s_)) names += (names.empty() ? "" : ", ") + n;
    status_.result = {Outcome::CTRL_STOPPED, "sensors went silent: " + names};
  } else if (!localizer_.healthy(now_s_)) {
    status_.result = {Outcome::CTRL_STOPPED, "localization unhealthy: " + localizer_.reason()};
  } else if (code != 0) {
    status_.result = {static_cast<Outcome>(code),
                      code == static_cast<int>(bipednav::code(last_failure_.outcome)) ? last_failure_.message : ""};
  } else if (!last_failure_.ok()) {
    status_.result = last_failure_;
  } else {
    status_.result = {Outcome::CTRL_FAILURE, "navigation failed"};
  }
}

}  // namespace bipednav::navigation
