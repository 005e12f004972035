#include "bench/scenario_odometry.hpp"

#include <algorithm>
#include <filesystem>
#include <numeric>
#include <optional>
#include <vector>

#include "bench/odometry_route.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/localization/drift_metrics.hpp"
#include "bipednav/localization/loam.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/scenario.hpp"
#include "bipednav/sim/simulation.hpp"

namespace bipednav::bench {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using localization::Drift;

json drift_json(const Drift& d) {
  return {{"translation_error_m", d.translation_error_m},
          {"translation_drift_percent", d.translation_percent},
          {"yaw_error_deg", d.yaw_error_deg},
          {"yaw_drift_deg_per_10m", d.yaw_deg_per_10m},
          {"height_error_m", d.height_error_m},
          {"max_translation_error_m", d.max_translation_error_m}};
}

}  // namespace

json run_scenario_odometry(const ScenarioOdometryOptions& o) {
  const sim::Scenario scenario = sim::load_scenario(o.scenario);
  const RobotProfile robot = navigation::load_robot(scenario.robot, o.config_dir);
  const SensorMount* mount = robot.sensor("lidar");
  if (!mount || mount->type != "vlp16") throw Error("robot '" + robot.name + "' has no vlp16 mount named 'lidar'");
  const SE3 T_base_lidar = mount->T_base_sensor();
  sim::SimulationParams sp;
  sp.seed = scenario.seed;
  sp.enable_depth = false;
  sim::Simulation sim(scenario.world, robot, scenario.start, sp);
  const OdometryRoute planned = route_for(o.waypoints, scenario, robot);
  const std::vector<Eigen::Vector2d>& route = planned.waypoints;
  const double v = o.speed_mps > 0 ? std::min(o.speed_mps, robot.limits.max_vel_x_mps) : robot.limits.max_vel_x_mps;
  const double t_end = o.duration_s > 0 ? o.duration_s : scenario.time_limit_s;

  std::optional<localization::Loam> loam;
  std::optional<SE3> odom_anchor, last_odom_lidar;
  SE3 odom = SE3::Identity(), T_world_first = SE3::Identity();
  std::vector<SE3> truth, est_loam, est_odom;
  std::vector<double> odo_ms, map_ms;
  std::size_t next = 0, unhealthy = 0, degenerate = 0;
  while (sim.now_s() < t_end && next < route.size()) {
    while (next < route.size() && (route[next] - sim.true_pose().position()).norm() < 0.2) ++next;
    const Twist cmd = next < route.size() && sim.now_s() >= 0.1 ? steer(sim.true_pose(), route[next], v) : Twist{};
    const SensorFrame f = sim.step(cmd);
    if (f.odometry) odom = se3_from_pose2(f.odometry->T_odom_base);
    if (!f.lidar) continue;
    const SE3 T_world_base = se3_from_pose2(sim.true_pose());
    if (!loam) {
      // LoamParams' defaults, or the file overlaid on the robot's defaults as `run --params` loads it.
      localization::LoamParams lp;
      if (!o.params.empty()) {
        runner::RunOptions ro;
        ro.params_file = o.params;
        lp = runner::navigator_params(robot, ro).localization.loam;
      }
      lp.planar_motion = lp.planar_motion || o.planar;
      lp.T_world_lidar_initial = T_world_base * T_base_lidar;
      loam.emplace(lp);
      odom_anchor = odom;
      T_world_first = T_world_base;
    }
    const SE3 odom_lidar = odom * T_base_lidar;
    std::optional<SE3> prior;
    if (!o.no_prior && last_odom_lidar) prior = last_odom_lidar->inverse() * odom_lidar;
    last_odom_lidar = odom_lidar;
    const localization::LoamOutput out = loam->process(*f.lidar, prior);
    unhealthy += out.healthy ? 0 : 1;
    degenerate += out.degenerate ? 1 : 0;
    odo_ms.push_back(out.odometry_ms);
    if (out.mapped) map_ms.push_back(out.mapping_ms);
    truth.push_back(T_world_base);
    est_loam.push_back(out.T_world_lidar * T_base_lidar.inverse());
    est_odom.push_back(T_world_first * odom_anchor->inverse() * odom);
  }
  if (truth.empty()) throw Error("no LiDAR sweep was produced (is --duration long enough?)");
  const Drift dl = localization::trajectory_drift(truth, est_loam);
  const Drift dd = localization::trajectory_drift(truth, est_odom);
  const auto mean = [](const std::vector<double>& x) {
    return x.empty() ? 0.0 : std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
  };
  json j = {{"scenario", scenario.name},
            {"simulated_s", sim.now_s()},
            {"distance_m", dl.distance_m},
            {"sweeps", truth.size()},
            {"route", planned.source},
            {"route_waypoints", route.size()},
            {"route_completed", next >= route.size()},
            {"contacts", sim.contacts().size()},
            {"motion_prior", !o.no_prior},
            {"planar_motion", o.planar},
            {"unhealthy_sweeps", unhealthy},
            {"degenerate_sweeps", degenerate},
            {"loam", drift_json(dl)},
            {"odometry", drift_json(dd)},
            {"loam_odometry_mean_ms", mean(odo_ms)},
            {"loam_mapping_mean_ms", mean(map_ms)}};
  return j;
}

}  // namespace bipednav::bench
