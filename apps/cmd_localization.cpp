// `bipednav register`, `bipednav odometry` on a scenario (bench/scenario_odometry; a recording:
// apps/cmd_odometry) and `bipednav bench localization` (the harness is bench/localization).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "apps/cmd_odometry.hpp"
#include "apps/commands.hpp"
#include "bench/localization.hpp"
#include "bench/scenario_odometry.hpp"
#include "bipednav/common/angles.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/localization/gicp.hpp"
#include "bipednav/sim/scenario_files.hpp"

namespace bipednav::app {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

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
  bench::ScenarioOdometryOptions run;
  bool json_out = false;
};

void run_odometry(const OdometryOptions& o) {
  const json j = bench::run_scenario_odometry(o.run);
  if (j["route"] == "straight (no goal)" && !o.json_out)
    std::fprintf(stderr, "note: scenario '%s' has no goal; driving straight ahead\n",
                 j["scenario"].get<std::string>().c_str());
  print_figures(o.json_out, j, [&] {
    std::printf(
        "%s: %.1f m in %.1f s, %zu sweeps. LOAM: %.2f %% of distance, %.3f deg per 10 m. Raw odometry: %.2f %%, "
        "%.3f deg per 10 m\n",
        j["scenario"].get<std::string>().c_str(), j["distance_m"].get<double>(), j["simulated_s"].get<double>(),
        j["sweeps"].get<std::size_t>(), j["loam"]["translation_drift_percent"].get<double>(),
        j["loam"]["yaw_drift_deg_per_10m"].get<double>(), j["odometry"]["translation_drift_percent"].get<double>(),
        j["odometry"]["yaw_drift_deg_per_10m"].get<double>());
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
  d->add_option("path", odo->run.scenario,
                "Recording (a KITTI/PCD/PLY folder or a .bag), or a scenario name or YAML file to simulate")
      ->required();
  d->add_option("--duration", odo->run.duration_s, "Scenario: simulated seconds (default: until the route is done)")
      ->check(check::positive());
  d->add_option("--waypoints", odo->run.waypoints,
                "Scenario: route as 'x,y x,y ...' (default: the widest route from the start through the goals, "
                "straight ahead without goals)");
  d->add_option("--speed", odo->run.speed_mps, "Scenario: forward speed in m/s (default: the robot's maximum)")
      ->check(check::positive());
  d->add_option("--config-dir", odo->run.config_dir,
                "Scenario: directory of robot profiles (default: the installed config/)");
  d->add_flag("--no-prior", odo->run.no_prior, "Scenario: do not give LOAM the odometry as a motion prior");
  d->add_flag("--planar", odo->run.planar, "Scenario: LOAM keeps the LiDAR's height, roll and pitch (flat floor)");
  add_json_flag(d, odo->json_out);
  d->add_option(
       "--params", odo->run.params,
       "Navigation parameters file (the layout of `bipednav params`): LOAM's parameters are its "
       "localization.loam, over the robot's defaults as `run --params` reads it (default: LoamParams' defaults; "
       "a recording: config/lidar/<lidar>.yaml when it exists)")
      ->check(CLI::ExistingFile);
  add_recorded_odometry_options(*d, *rec);
  d->callback([d, odo, rec] {
    const bool recording = is_recording(odo->run.scenario);
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
      rec->path = odo->run.scenario;
      rec->params = odo->run.params;
      rec->json_out = odo->json_out;
      run_recorded_odometry_command(*rec);
      return;
    }
    odo->run.scenario = sim::resolve_scenario(odo->run.scenario).string();
    run_odometry(*odo);
  });

  add_localization_bench(bench);
}

}  // namespace bipednav::app
