#include "apps/cmd_odometry.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "apps/cli_checks.hpp"
#include "apps/cli_json.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/io/trajectory_file.hpp"
#include "bipednav/perception/lidar_model.hpp"
#include "bipednav/viz/trajectory_plot.hpp"
#ifdef BIPEDNAV_WITH_ROSBAG
#include "ros/bag_sweeps.hpp"
#endif

namespace bipednav::app {

namespace fs = std::filesystem;
using json = nlohmann::json;

bool is_recording(const std::string& path) {
  return fs::is_directory(path) || (fs::is_regular_file(path) && fs::path(path).extension() == ".bag");
}

void add_recorded_odometry_options(CLI::App& d, RecordedOdometryCli& o) {
  d.add_option("--format", o.format, "Recording format (default: from the content)")
      ->check(CLI::IsMember({"kitti", "pcd", "ply", "rosbag"}));
  d.add_option("--topic", o.topic, "rosbag: the sensor_msgs/PointCloud2 topic (default: the only one)");
  d.add_option("--lidar", o.lidar, "LiDAR model: ring table, rate, rotation (default: hdl64 for KITTI, else vlp16)")
      ->check(CLI::IsMember(perception::lidar_model_names()));
  d.add_option("--gt", o.gt, "Reference poses, one per sweep, LiDAR frame (TUM or KITTI file; KITTI: poses.txt)")
      ->check(CLI::ExistingFile);
  d.add_option("--method", o.method, "loam, or gicp (scan-to-scan GICP baseline)")
      ->capture_default_str()
      ->check(CLI::IsMember({"loam", "gicp"}));
  d.add_option("--out", o.out, "Output folder: poses (TUM, KITTI), map.pcd, trajectory.png, run.json");
  d.add_option("--deskew", o.deskew, "Per-point times from azimuth for sweeps without: auto (not KITTI), on, off")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "on", "off"}));
  d.add_option("--max-sweeps", o.max_sweeps, "Sweeps to run (default: all)")->check(check::integer_at_least(1));
  d.add_option("--map-voxel", o.map_voxel_m, "Map leaf size in m")->capture_default_str()->check(check::positive());
  d.add_option("--gicp-voxel", o.gicp_voxel_m, "gicp: input leaf size in m")
      ->capture_default_str()
      ->check(check::positive());
  d.add_flag("--registration-reference", o.registration_reference,
             "Also evaluate against the sweeps' own trajectory: each registered directly onto the first (GICP)");
  d.add_option("--rpe-distance", o.rpe_distance_m, "RPE path distance in m")
      ->capture_default_str()
      ->check(check::positive());
}

runner::SweepSequence open_recording(const RecordedOdometryCli& o, std::string& format) {
  const io::SweepFormat f = o.format.empty() ? io::detect_sweep_format(o.path) : io::sweep_format_from_string(o.format);
  format = io::to_string(f);
  runner::SweepSequence seq;
  if (f == io::SweepFormat::rosbag) {
#ifdef BIPEDNAV_WITH_ROSBAG
    seq = ros1::open_bag_sweeps(o.path, o.topic);
#else
    throw Error("--format rosbag: this build has no ROS 1 (rosbag) support");
#endif
  } else {
    seq = runner::sweep_sequence_from_files(io::open_sweep_files(o.path, f));
  }
  if (!o.gt.empty()) {
    const io::Trajectory gt = io::read_trajectory(o.gt);
    if (gt.poses.size() < seq.count)
      throw FileError(
          o.gt, "",
          "expected a pose per sweep (" + std::to_string(seq.count) + "), got " + std::to_string(gt.poses.size()));
    seq.truth.assign(gt.poses.begin(), gt.poses.begin() + static_cast<std::ptrdiff_t>(seq.count));
  }
  return seq;
}

namespace {

double percentile(std::vector<double> x, double q) {
  if (x.empty()) return 0.0;
  std::sort(x.begin(), x.end());
  return x[static_cast<std::size_t>(q * static_cast<double>(x.size() - 1) + 0.5)];
}

double mean_of(const std::vector<double>& x) {
  double s = 0.0;
  for (const double v : x) s += v;
  return x.empty() ? 0.0 : s / static_cast<double>(x.size());
}

json kitti_json(const localization::KittiError& k) {
  return {{"translation_percent", k.translation_percent},
          {"rotation_deg_per_m", k.rotation_deg_per_m},
          {"segments", k.segments},
          {"lengths_m", k.lengths_used_m}};
}

json evaluation_json(const runner::TrajectoryEvaluation& e) {
  json short_k = kitti_json(e.kitti_short);
  short_k["step_frames"] = e.kitti_short_step_frames;
  return {{"distance_m", e.distance_m},
          {"end_point_error_m", e.end_point_error_m},
          {"end_point_error_percent", e.distance_m > 0.0 ? 100.0 * e.end_point_error_m / e.distance_m : 0.0},
          {"ate_rmse_m", e.ate.translation_m.rmse},
          {"ate_max_m", e.ate.translation_m.max},
          {"rpe_1_frame",
           {{"translation_rmse_m", e.rpe_frame.translation_m.rmse},
            {"rotation_rmse_deg", e.rpe_frame.rotation_deg.rmse},
            {"pairs", e.rpe_frame.translation_m.count}}},
          {"rpe_distance",
           {{"distance_m", e.rpe_distance_m},
            {"translation_rmse_m", e.rpe_distance.translation_m.rmse},
            {"rotation_rmse_deg", e.rpe_distance.rotation_deg.rmse},
            {"pairs", e.rpe_distance.translation_m.count}}},
          {"kitti_100_800m", kitti_json(e.kitti)},
          {"kitti_whole_metres", short_k}};
}

std::vector<Eigen::Vector2d> xy_of(const std::vector<SE3>& poses) {
  std::vector<Eigen::Vector2d> xy;
  for (const SE3& T : poses) xy.push_back(T.translation().head<2>());
  return xy;
}

void write_outputs(const fs::path& out, const runner::RecordedOdometryResult& r, const std::string& method) {
  fs::create_directories(out);
  io::write_tum_trajectory(out / "poses_tum.txt", r.stamps_s, r.estimate);
  io::write_kitti_trajectory(out / "poses_kitti.txt", r.estimate);
  io::write_pcd(out / "map.pcd", r.map);
  std::vector<viz::PlotLine> lines;
  if (!r.truth.empty()) lines.push_back({"ground truth", viz::colors::kBlack, xy_of(r.truth)});
  lines.push_back({method == "loam" ? "LOAM estimate" : "GICP estimate", viz::colors::kRed, xy_of(r.estimate)});
  viz::write_trajectory_plot(out / "trajectory.png", lines, "bipednav odometry (top view, x right, y up)");
}

}  // namespace

json run_recorded_odometry_command(const RecordedOdometryCli& o) {
  std::string format;
  const runner::SweepSequence seq = open_recording(o, format);
  runner::RecordedOdometryOptions ro;
  ro.lidar = !o.lidar.empty() ? o.lidar : format == "kitti" ? "hdl64" : "vlp16";
  ro.method = o.method;
  fs::path params_used;
  ro.loam = runner::loam_params_for_lidar(ro.lidar, o.params, &params_used);
  ro.gicp_voxel_m = o.gicp_voxel_m;
  // KITTI odometry's sweeps are motion-compensated already: times would de-skew them twice.
  ro.deskew = o.deskew == "on" || (o.deskew == "auto" && format != "kitti");
  ro.map_voxel_m = o.map_voxel_m;
  ro.max_sweeps = o.max_sweeps;
  ro.progress = isatty(STDERR_FILENO) != 0;
  const runner::RecordedOdometryResult r = runner::run_recorded_odometry(seq, ro);
  fs::path input = fs::path(o.path).lexically_normal();
  if (input.filename().empty()) input = input.parent_path();
  json j = {{"input", input.filename().string()},
            {"format", format},
            {"lidar", ro.lidar},
            {"method", ro.method},
            {"loam_params_file", params_used.empty() ? "" : params_used.filename().string()},
            {"sweeps", r.estimate.size()},
            {"points_per_sweep", r.points / std::max<std::size_t>(1, r.estimate.size())},
            {"ring_method", perception::to_string(r.ring_method)},
            {"rings", r.ring_count},
            {"times_from_azimuth", r.times_from_azimuth},
            {"unhealthy_sweeps", r.unhealthy},
            {"degenerate_sweeps", r.degenerate},
            {"per_sweep_median_ms", percentile(r.method_ms, 0.5)},
            {"per_sweep_p95_ms", percentile(r.method_ms, 0.95)},
            {"per_sweep_cpu_median_ms", percentile(r.method_cpu_ms, 0.5)},
            {"mapping_mean_ms", mean_of(r.mapping_ms)},
            {"preprocess_median_ms", percentile(r.preprocess_ms, 0.5)},
            {"map_points", r.map.size()},
            {"evaluation", nullptr}};
  if (!r.truth.empty())
    j["evaluation"] = evaluation_json(runner::evaluate_trajectory(r.truth, r.estimate, o.rpe_distance_m));
  if (o.registration_reference)
    j["evaluation_against_registration"] = evaluation_json(
        runner::evaluate_trajectory(runner::direct_registration_trajectory(seq), r.estimate, o.rpe_distance_m));
  if (!o.out.empty()) {
    write_outputs(o.out, r, ro.method);
    std::ofstream(fs::path(o.out) / "run.json") << j.dump(2) << "\n";
  }
  if (o.json_out) {
    print_json(j);
  } else if (!r.truth.empty()) {
    const json& e = j["evaluation"];
    std::printf(
        "%s (%s, %s): %zu sweeps, %.2f m; end-point error %.3f m, ATE %.3f m, KITTI %.2f %% / %.4f deg/m "
        "(whole-metre segments); %.1f ms CPU per sweep (median)\n",
        o.path.c_str(), format.c_str(), ro.method.c_str(), r.estimate.size(), e["distance_m"].get<double>(),
        e["end_point_error_m"].get<double>(), e["ate_rmse_m"].get<double>(),
        e["kitti_whole_metres"]["translation_percent"].get<double>(),
        e["kitti_whole_metres"]["rotation_deg_per_m"].get<double>(), j["per_sweep_cpu_median_ms"].get<double>());
  } else {
    std::printf("%s (%s, %s): %zu sweeps, no reference poses; %.1f ms CPU per sweep (median)\n", o.path.c_str(),
                format.c_str(), ro.method.c_str(), r.estimate.size(), j["per_sweep_cpu_median_ms"].get<double>());
  }
  return j;
}

}  // namespace bipednav::app
