// `bipednav register`, `bipednav odometry` on a scenario (a recording: apps/cmd_odometry) and `bipednav
// bench localization` (the harness is bench/localization; the route both drive is bench/odometry_route).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "apps/cmd_odometry.hpp"
#include "apps/commands.hpp"
#include "bench/localization.hpp"
#include "bench/odometry_route.hpp"
#include "bipednav/common/angles.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/io/robot_profile_yaml.hpp"
#include "bipednav/localization/drift_metrics.hpp"
#include "bipednav/localization/gicp.hpp"
#include "bipednav/localization/loam.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/scenario.hpp"
#include "bipednav/sim/scenario_files.hpp"
#include "bipednav/sim/simulation.hpp"

namespace bipednav::app {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using localization::Drift;

json matrix_json(const SE3& T) {
  json rows = json::array();
  for (int r = 0; r < 4; ++r) {
    json row = json::array();
    for (int c = 0; c < 4; ++c) row.push_back(T.matrix()(r, c));
    rows.push_back(row);
  }
  return rows;
}

struct RegisterOptions {
  std::string source, target;
  double voxel_m = 0.2;
  int threads = 1;
  bool json_out = false;
};

// Returns whether GICP converged (the exit status).
bool run_register(const RegisterOptions& o) {
  const PointCloud source = bench::load_cloud(o.source, o.voxel_m), target = bench::load_cloud(o.target, o.voxel_m);
  localization::GicpParams p;
  p.threads = o.threads;
  const localization::GicpResult r = localization::gicp_align(source, target, SE3::Identity(), p);
  const json j = {{"T_target_source", matrix_json(r.T_target_source)},
                  {"fitness", r.fitness},
                  {"converged", r.converged},
                  {"iterations", r.iterations},
                  {"correspondences", r.correspondences},
                  {"source_points", source.size()},
                  {"target_points", target.size()},
                  {"time_ms", r.time_ms}};
  print_figures(o.json_out, j, [&] {
    const Eigen::Vector3d t = r.T_target_source.translation();
    const Eigen::Vector3d rpy = matrix_to_rpy(r.T_target_source.rotation());
    std::printf(
        "T_target_source: t = (%.4f, %.4f, %.4f) m, rpy = (%.3f, %.3f, %.3f) deg; fitness %.4f m^2, %s after %d "
        "iterations, %.1f ms\n",
        t.x(), t.y(), t.z(), rad2deg(rpy.x()), rad2deg(rpy.y()), rad2deg(rpy.z()), r.fitness,
        r.converged ? "converged" : "NOT converged", r.iterations, r.time_ms);
  });
  return r.converged;
}

struct OdometryOptions {
  std::string scenario;
  std::string config_dir;
  std::string waypoints;
  double duration_s = 0.0;  // 0: until the route is done (or the scenario's time limit)
  double speed_mps = 0.0;   // 0: the robot's maximum
  bool no_prior = false;
  bool planar = false;  // LOAM keeps the LiDAR's height, roll and pitch (LoamParams::planar_motion)
  bool json_out = false;
  std::string params;  // a navigation parameters file: LOAM's parameters from its localization.loam
};

json drift_json(const Drift& d) {
  return {{"translation_error_m", d.translation_error_m},
          {"translation_drift_percent", d.translation_percent},
          {"yaw_error_deg", d.yaw_error_deg},
          {"yaw_drift_deg_per_10m", d.yaw_deg_per_10m},
          {"height_error_m", d.height_error_m},
          {"max_translation_error_m", d.max_translation_error_m}};
}

void run_odometry(const OdometryOptions& o) {
  const sim::Scenario scenario = sim::load_scenario(o.scenario);
  const fs::path cfg =
      !o.config_dir.empty() ? fs::path(o.config_dir) : fs::path(o.scenario).parent_path() / ".." / "config";
  const RobotProfile robot = io::load_robot_profile(cfg / (scenario.robot + ".yaml"));
  const SensorMount* mount = robot.sensor("lidar");
  if (!mount || mount->type != "vlp16") throw Error("robot '" + robot.name + "' has no vlp16 mount named 'lidar'");
  const SE3 T_base_lidar = mount->T_base_sensor();
  sim::SimulationParams sp;
  sp.seed = scenario.seed;
  sp.enable_depth = false;
  sim::Simulation sim(scenario.world, robot, scenario.start, sp);
  const bench::OdometryRoute planned = bench::route_for(o.waypoints, scenario, robot);
  if (planned.source == "straight (no goal)" && !o.json_out)
    std::fprintf(stderr, "note: scenario '%s' has no goal; driving straight ahead\n", scenario.name.c_str());
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
    const Twist cmd =
        next < route.size() && sim.now_s() >= 0.1 ? bench::steer(sim.true_pose(), route[next], v) : Twist{};
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
  const json j = {{"scenario", scenario.name},
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
  print_figures(o.json_out, j, [&] {
    std::printf(
        "%s: %.1f m in %.1f s, %zu sweeps. LOAM: %.2f %% of distance, %.3f deg per 10 m. Raw odometry: %.2f %%, "
        "%.3f deg per 10 m\n",
        scenario.name.c_str(), dl.distance_m, sim.now_s(), truth.size(), dl.translation_percent, dl.yaw_deg_per_10m,
        dd.translation_percent, dd.yaw_deg_per_10m);
  });
}

struct LocalizationBenchArgs {
  bench::LocalizationBenchOptions options;
  bool json_out = false;
};

void add_localization_bench(CLI::App& bench) {
  auto o = std::make_shared<LocalizationBenchArgs>();
  CLI::App* b = bench.add_subcommand(
      "localization",
      "LOAM per simulated VLP-16 sweep, GICP on the scan pair, LOAM and GICP odometry on KITTI HDL-64E sweeps");
  b->add_option("--scenario", o->options.scenario, "Scenario for the simulated sweeps")->capture_default_str();
  b->add_option("--data-dir", o->options.data_dir, "Directory of the fast_gicp scan pair");
  b->add_option("--kitti-dir", o->options.kitti.kitti_dir,
                "KITTI odometry folder for the HDL-64E rows (skipped when absent)");
  b->add_option("--humanoid-scenario", o->options.humanoid.scenario, "Footstep scenario of the humanoid drift rows")
      ->capture_default_str();
  b->add_option("--sweeps", o->options.sweeps, "Simulated sweeps for LOAM")
      ->capture_default_str()
      ->check(CLI::Range(2, 10000));
  add_json_flag(b, o->json_out);
  b->callback([o] {
    const json j = bench::run_localization_bench(o->options);
    print_figures(o->json_out, j, [&] {
      std::printf("LOAM odometry median %.2f ms/sweep (goal 20); GICP %.1f ms (reference 410 ms)\n",
                  j["loam_odometry_median_ms"].get<double>(), j["gicp_median_ms"].get<double>());
    });
    report_task(bench_goals_met(j));
  });
}

}  // namespace

void add_localization_commands(CLI::App& app, CLI::App& bench) {
  auto reg = std::make_shared<RegisterOptions>();
  CLI::App* r = app.add_subcommand("register", "Align SOURCE to TARGET with Generalized-ICP (from identity)");
  r->add_option("source", reg->source, "Source cloud (.pcd or .ply)")->required()->check(CLI::ExistingFile);
  r->add_option("target", reg->target, "Target cloud (.pcd or .ply)")->required()->check(CLI::ExistingFile);
  r->add_option("--voxel", reg->voxel_m, "Voxel down-sampling leaf in m (0: none)")
      ->capture_default_str()
      ->check(check::non_negative());
  r->add_option("--threads", reg->threads, "Worker threads")->capture_default_str()->check(check::integer_in(1, 256));
  add_json_flag(r, reg->json_out);
  r->callback([reg] { report_task(run_register(*reg)); });

  auto odo = std::make_shared<OdometryOptions>();
  auto rec = std::make_shared<RecordedOdometryCli>();
  CLI::App* d = app.add_subcommand(
      "odometry",
      "LOAM (or GICP) odometry on a recording (KITTI, PCD or PLY folder, rosbag) against its reference poses, or "
      "driving a scenario in the simulator (LOAM and raw odometry drift)");
  d->add_option("path", odo->scenario,
                "Recording (a KITTI/PCD/PLY folder or a .bag), or a scenario name or YAML file to simulate")
      ->required();
  d->add_option("--duration", odo->duration_s, "Scenario: simulated seconds (default: until the route is done)")
      ->check(check::positive());
  d->add_option("--waypoints", odo->waypoints,
                "Scenario: route as 'x,y x,y ...' (default: the widest route from the start through the goals, "
                "straight ahead without goals)");
  d->add_option("--speed", odo->speed_mps, "Scenario: forward speed in m/s (default: the robot's maximum)")
      ->check(check::positive());
  d->add_option("--config-dir", odo->config_dir,
                "Scenario: directory of robot profiles (default: <scenario>/../config)");
  d->add_flag("--no-prior", odo->no_prior, "Scenario: do not give LOAM the odometry as a motion prior");
  d->add_flag("--planar", odo->planar, "Scenario: LOAM keeps the LiDAR's height, roll and pitch (flat floor)");
  add_json_flag(d, odo->json_out);
  d->add_option(
       "--params", odo->params,
       "Navigation parameters file (the layout of `bipednav params`): LOAM's parameters are its "
       "localization.loam, over the robot's defaults as `run --params` reads it (default: LoamParams' defaults; "
       "a recording: config/lidar/<lidar>.yaml when it exists)")
      ->check(CLI::ExistingFile);
  add_recorded_odometry_options(*d, *rec);
  d->callback([d, odo, rec] {
    const bool recording = is_recording(odo->scenario);
    // Options of the other kind of input are an error, not silently dropped.
    const char* const scenario_only[] = {"--duration",   "--waypoints", "--speed",
                                         "--config-dir", "--no-prior",  "--planar"};
    const char* const recording_only[] = {"--format",    "--topic",      "--lidar",        "--gt",
                                          "--method",    "--out",        "--deskew",       "--max-sweeps",
                                          "--map-voxel", "--gicp-voxel", "--rpe-distance", "--registration-reference"};
    std::string wrong;
    for (const char* name : recording ? std::vector<const char*>(std::begin(scenario_only), std::end(scenario_only))
                                      : std::vector<const char*>(std::begin(recording_only), std::end(recording_only)))
      if (d->get_option(name)->count() > 0) wrong += (wrong.empty() ? "" : ", ") + std::string(name);
    if (!wrong.empty())
      throw Error(wrong + (recording ? ": only for a simulated scenario, not for a recording"
                                     : ": only for a recording (a folder or a .bag), not for a scenario"));
    if (recording) {
      rec->path = odo->scenario;
      rec->params = odo->params;
      rec->json_out = odo->json_out;
      run_recorded_odometry_command(*rec);
      return;
    }
    odo->scenario = sim::resolve_scenario(odo->scenario).string();
    run_odometry(*odo);
  });

  add_localization_bench(bench);
}

}  // namespace bipednav::app
