#include "ros/bag_recorder.hpp"

#include <rosbag/bag.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_msgs/TFMessage.h>

#include "bipednav/navigation/robot_loading.hpp"
#include "ros/conversions.hpp"

namespace bipednav::ros1 {

void BagRecorderParams::validate() const {
  require(map_period_s > 0.0, "map_period_s", "> 0");
  require(local_period_s > 0.0, "local_period_s", "> 0");
  require(path_period_s > 0.0, "path_period_s", "> 0");
}

BagRecorder::BagRecorder(const std::filesystem::path& file, const RobotProfile& robot, BagRecorderParams params)
    : params_(std::move(params)), robot_(robot), bag_(std::make_unique<rosbag::Bag>()) {
  params_.validate();
  ros::Time::init();  // rosbag stamps need the time system, no master
  try {
    bag_->open(file.string(), rosbag::bagmode::Write);
    if (params_.compress) bag_->setCompression(rosbag::compression::LZ4);
  } catch (const std::exception& e) {
    throw FileError(file.string(), "", std::string("cannot open the bag for writing: ") + e.what());
  }
  tf2_msgs::TFMessage mounts;
  for (const auto& m : robot_.sensors)
    mounts.transforms.push_back(to_transform(m.T_base_sensor(), params_.base_frame, m.name, 0.0));
  if (!mounts.transforms.empty()) write("/tf_static", 0.0, mounts);
}

BagRecorder::~BagRecorder() { close(); }

void BagRecorder::close() {
  if (bag_ && bag_->isOpen()) bag_->close();
}

template <typename M>
void BagRecorder::write(const std::string& topic, double stamp_s, const M& msg) {
  bag_->write(topic, to_time(std::max(stamp_s, 1e-6)), msg);
  ++messages_;
}

void BagRecorder::record(const sim::Simulation& sim, const SensorFrame& frame, const navigation::Navigator& nav,
                         const Twist& cmd) {
  const double t = frame.stamp_s;
  const auto& p = params_;
  rosgraph_msgs::Clock clock;
  clock.clock = to_time(t);
  write("/clock", t, clock);
  tf2_msgs::TFMessage tf;
  tf.transforms.push_back(to_transform(nav.T_map_odom(), p.map_frame, p.odom_frame, t));
  if (frame.odometry) {
    tf.transforms.push_back(to_transform(frame.odometry->T_odom_base, p.odom_frame, p.base_frame, t));
    write("/odom", t, to_msg(*frame.odometry, p.odom_frame, p.base_frame));
    Odometry truth{t, sim.true_pose(), sim.true_velocity()};
    write("/ground_truth", t, to_msg(truth, p.map_frame, p.base_frame + "_truth"));
  }
  write("/tf", t, tf);
  write("/cmd_vel", t, to_msg(cmd));
  if (frame.lidar) write("/" + frame.lidar->frame_id + "/points", t, to_msg(*frame.lidar));
  if (p.record_depth)
    for (const auto& d : frame.depth) {
      auto msg = to_msg(d.cloud);
      msg.header.frame_id = d.camera;
      write("/" + d.camera + "/points", t, msg);
    }
  if (t >= next_map_s_) {
    next_map_s_ = t + p.map_period_s;
    write("/global_costmap", t, to_msg(nav.global_map().costmap(), p.map_frame, t));
  }
  if (t >= next_local_s_) {
    next_local_s_ = t + p.local_period_s;
    write("/local_costmap", t, to_msg(nav.local_map().costmap(), p.map_frame, t));
    MarkerInput m{p.map_frame,
                  t,
                  nav.pose(),
                  robot_.footprint_radius_m,
                  nav.goal(),
                  &nav.local_map().costmap(),
                  &nav.local_trajectory()};
    write("/markers", t, to_markers(m));
  }
  if (t >= next_path_s_) {
    next_path_s_ = t + p.path_period_s;
    write("/global_plan", t, to_msg(nav.global_path(), t));
    write("/local_plan", t, to_msg(nav.local_trajectory(), t));
  }
}

// A lean copy of the closed loop (goals at their times, step, tick, record): the runner has no
// per-step hook yet. With one (RunOptions::on_step), this becomes a call to run_scenario.
BagRunSummary run_scenario_to_bag(const sim::Scenario& scenario, const runner::RunOptions& o,
                                  const std::filesystem::path& bag_file, const BagRecorderParams& bag_params) {
  const RobotProfile robot = navigation::load_robot(o.robot.empty() ? scenario.robot : o.robot, o.config_dir);
  sim::SimulationParams sp;
  sp.seed = o.seed.value_or(scenario.seed);
  sim::Simulation sim(scenario.world, robot, scenario.start, sp);
  auto params = runner::navigator_params(robot, o);
  params.server.goal.xy_tolerance_m = scenario.goal_tolerance_m;
  params.server.goal.yaw_tolerance_rad = scenario.goal_tolerance_rad;
  navigation::Navigator nav(params, robot, runner::global_geometry_for(scenario, params.global_map.resolution_m),
                            scenario.start);
  BagRecorder recorder(bag_file, robot, bag_params);
  const double limit = o.time_limit_s.value_or(scenario.time_limit_s);
  const sim::TimedGoal* active = nullptr;
  Twist cmd;
  while (sim.now_s() < limit) {
    const sim::TimedGoal* g = scenario.goal_at(sim.now_s());
    if (g && g != active) nav.set_goal((active = g)->pose);
    SensorFrame frame = sim.step(cmd);
    cmd = nav.tick(frame);
    recorder.record(sim, frame, nav, cmd);
    sim.recycle(std::move(frame));  // its clouds' buffers hold the next frames' clouds
    const bool last_goal = scenario.goals.empty() || active == &scenario.goals.back();
    const auto state = nav.status().state;
    if (last_goal && (state == navigation::NavState::SUCCEEDED || state == navigation::NavState::FAILED)) break;
  }
  recorder.close();
  BagRunSummary out;
  out.status = nav.status();
  out.time_s = sim.now_s();
  out.messages = recorder.messages();
  out.collided = sim.first_collision().has_value();
  return out;
}

}  // namespace bipednav::ros1
