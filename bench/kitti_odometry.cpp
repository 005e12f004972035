#include "bench/kitti_odometry.hpp"

#include <algorithm>
#include <filesystem>
#include <vector>

#include "bipednav/io/kitti_sequence.hpp"
#include "bipednav/io/sweep_folder.hpp"
#include "bipednav/runner/recorded_odometry.hpp"

namespace bipednav::bench {

namespace {

using json = nlohmann::json;

double median_of(std::vector<double> x) {
  if (x.empty()) return 0.0;
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

double mean_of_ms(const std::vector<double>& x) {
  double s = 0.0;
  for (const double v : x) s += v;
  return x.empty() ? 0.0 : s / static_cast<double>(x.size());
}

// Three runs of one method over the sweeps (the same trajectory each time): CPU times of all.
runner::RecordedOdometryResult timed_runs(const runner::SweepSequence& seq, const runner::RecordedOdometryOptions& o,
                                          std::vector<double>& cpu_ms) {
  runner::RecordedOdometryResult r;
  for (int rep = 0; rep < 3; ++rep) {
    r = runner::run_recorded_odometry(seq, o);
    cpu_ms.insert(cpu_ms.end(), r.method_cpu_ms.begin(), r.method_cpu_ms.end());
  }
  return r;
}

}  // namespace

json bench_kitti_odometry(const KittiOdometryOptions& options) {
  constexpr double kGoalMs = 25.0, kFloamMs = 59.0;  // issue goal; F-LOAM's reported time per sweep
  using std::filesystem::path;
  const path dir = !options.kitti_dir.empty() ? path(options.kitti_dir)
                                              : path(BIPEDNAV_SOURCE_DIR) / "tests/data/lidar/kitti00_f0-15";
  if (!io::is_kitti_sequence(dir))
    return {{"kitti_note", "skipped: no KITTI sweeps in " + dir.string() + " (give --kitti-dir)"},
            {"kitti_loam_cpu_median_ms", nullptr},
            {"kitti_gicp_cpu_median_ms", nullptr}};
  const io::SweepFiles files = io::open_sweep_files(dir, io::SweepFormat::kitti);
  // Read once: the timings are of the odometry, not of the disk.
  std::vector<PointCloud> sweeps;
  for (std::size_t i = 0; i < files.files.size(); ++i) sweeps.push_back(io::read_sweep(files, i));
  runner::SweepSequence seq;
  seq.format = "kitti";
  seq.count = sweeps.size();
  seq.truth = files.T_lidar0_lidar;
  seq.read = [&sweeps](std::size_t i) { return sweeps[i]; };
  runner::RecordedOdometryOptions o;
  o.lidar = "hdl64";
  o.loam = runner::loam_params_for_lidar("hdl64", {});
  o.deskew = false;  // KITTI odometry's sweeps are motion-compensated
  std::vector<double> loam_ms, gicp_ms;
  const runner::RecordedOdometryResult loam = timed_runs(seq, o, loam_ms);
  o.method = "gicp";
  const runner::RecordedOdometryResult gicp = timed_runs(seq, o, gicp_ms);
  const std::vector<SE3> own = runner::direct_registration_trajectory(seq);
  const runner::TrajectoryEvaluation l = runner::evaluate_trajectory(own, loam.estimate);
  const runner::TrajectoryEvaluation g = runner::evaluate_trajectory(own, gicp.estimate);
  json j = {{"kitti_sweeps", sweeps.size()},
            {"kitti_points_per_sweep", loam.points / std::max<std::size_t>(1, sweeps.size())},
            {"kitti_loam_cpu_median_ms", median_of(loam_ms)},
            {"kitti_loam_cpu_mean_ms", mean_of_ms(loam_ms)},  // mapping (1 Hz) amortised
            {"kitti_gicp_cpu_median_ms", median_of(gicp_ms)},
            {"kitti_gicp_voxel_m", o.gicp_voxel_m},
            {"kitti_loam_vs_gicp_speed_ratio", median_of(gicp_ms) / std::max(median_of(loam_ms), 1e-9)},
            {"goal_kitti_loam_cpu_median_ms", kGoalMs},
            {"meets_goal_kitti_loam_cpu_median", median_of(loam_ms) <= kGoalMs},
            {"reference_floam_ms", kFloamMs},
            {"kitti_direct_registration_path_m", l.distance_m},
            {"kitti_loam_end_point_error_m", l.end_point_error_m},
            {"kitti_loam_relative_translation_percent", l.kitti_short.translation_percent},
            {"kitti_loam_relative_rotation_deg_per_m", l.kitti_short.rotation_deg_per_m},
            {"kitti_gicp_end_point_error_m", g.end_point_error_m},
            {"kitti_gicp_relative_translation_percent", g.kitti_short.translation_percent},
            {"kitti_segment_lengths_m", l.kitti_short.lengths_used_m},
            {"kitti_note",
             "errors against the sweeps' direct registration onto the first (KITTI's metric over 1 m segments "
             "from every frame); poses.txt's path is 10 % longer than the sweeps' own, see kitti_poses_txt_*"}};
  if (!seq.truth.empty()) {
    const runner::TrajectoryEvaluation t = runner::evaluate_trajectory(loam.truth, loam.estimate);
    j["kitti_poses_txt_path_m"] = t.distance_m;
    j["kitti_poses_txt_loam_end_point_error_m"] = t.end_point_error_m;
    j["kitti_poses_txt_loam_relative_translation_percent"] = t.kitti_short.translation_percent;
  }
  return j;
}

}  // namespace bipednav::bench
