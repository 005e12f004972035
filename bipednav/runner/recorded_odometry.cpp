#include "bipednav/runner/recorded_odometry.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/cpu_time.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/common/progress.hpp"
#include "bipednav/navigation/navigator.hpp"
#include "bipednav/navigation/navigator_params_yaml.hpp"
#include "bipednav/perception/lidar_model.hpp"
#include "bipednav/perception/scan_times.hpp"
#include "bipednav/perception/voxel_grid.hpp"

namespace bipednav::runner {

namespace fs = std::filesystem;

SweepSequence sweep_sequence_from_files(io::SweepFiles files) {
  SweepSequence s;
  s.format = io::to_string(files.format);
  s.count = files.files.size();
  s.truth = files.T_lidar0_lidar;
  s.read = [f = std::move(files)](std::size_t i) { return io::read_sweep(f, i); };
  return s;
}

localization::LoamParams loam_params_for_lidar(const std::string& lidar, const fs::path& params_file,
                                               fs::path* used_file) {
  const perception::LidarModel model = perception::lidar_model(lidar);
  fs::path file = params_file;
  if (file.empty()) {
    const fs::path own = fs::path(navigation::config_dir()) / "lidar" / (lidar + ".yaml");
    if (fs::exists(own)) file = own;
  }
  navigation::NavigatorParams np;  // its localization.loam holds LoamParams' defaults
  np.behavior_tree = navigation::config_dir() + "/behavior_trees/navigate.xml";  // validated with the file
  np.localization.loam.odometry.scan_period_s = 1.0 / model.rate_hz;
  if (!file.empty()) navigation::apply_navigator_params_file(file, np);
  if (used_file) *used_file = file;
  return np.localization.loam;
}

void RecordedOdometryOptions::validate() const {
  perception::lidar_model(lidar);
  require(method == "loam" || method == "gicp", "method", "loam or gicp");
  loam.validate();
  gicp.validate();
  require(gicp_voxel_m > 0.0 && std::isfinite(gicp_voxel_m), "gicp_voxel_m", "> 0");
  require(map_voxel_m > 0.0 && std::isfinite(map_voxel_m), "map_voxel_m", "> 0");
}

namespace {

// The accumulated map: world-frame points, down-sampled whenever they have grown enough.
class MapAccumulator {
 public:
  explicit MapAccumulator(double leaf_m) {
    perception::VoxelGridParams vp;
    vp.leaf_size_m = Eigen::Vector3d::Constant(leaf_m);
    grid_ = perception::VoxelGrid(vp);
  }
  void add(const PointCloud& cloud_lidar, const SE3& T_world_lidar) {
    const Eigen::Matrix3f R = T_world_lidar.linear().cast<float>();
    const Eigen::Vector3f t = T_world_lidar.translation().cast<float>();
    for (const Eigen::Vector3f& p : cloud_lidar.points)
      if (p.allFinite()) raw_.points.push_back(R * p + t);
    if (raw_.size() > 2 * kept_ + 500000) compact();
  }
  PointCloud take() {
    compact();
    return std::move(raw_);
  }

 private:
  void compact() {
    PointCloud out;
    grid_.filter(raw_, out);
    raw_ = std::move(out);
    kept_ = raw_.size();
  }
  perception::VoxelGrid grid_;
  PointCloud raw_;
  std::size_t kept_ = 0;
};

// One odometry method behind a common step: the pose after a prepared sweep, its cost and health.
struct MethodStep {
  SE3 T_world_lidar = SE3::Identity();
  double ms = 0.0;          // all of the step
  double mapping_ms = 0.0;  // LOAM's mapping step, when it ran (part of ms)
  bool healthy = true, degenerate = false;
};

class OdometryMethod {
 public:
  OdometryMethod(const RecordedOdometryOptions& o, const SE3& T_world_first) {
    if (o.method == "loam") {
      localization::LoamParams lp = o.loam;
      lp.T_world_lidar_initial = T_world_first;
      lp.output_deskewed = true;
      loam_.emplace(lp);
    } else {
      gicp_.emplace(o.gicp, T_world_first);
      perception::VoxelGridParams vp;
      vp.leaf_size_m = Eigen::Vector3d::Constant(o.gicp_voxel_m);
      voxel_ = perception::VoxelGrid(vp);
    }
  }

  // The step's pose; `map_points` receives the sweep's points for the map (LiDAR frame at the pose).
  MethodStep step(const PointCloud& sweep, PointCloud& map_points) {
    MethodStep s;
    if (loam_) {
      localization::LoamOutput out = loam_->process(sweep);
      s = {out.T_world_lidar, out.odometry_ms + out.mapping_ms, out.mapping_ms, out.healthy, out.degenerate};
      map_points = std::move(out.deskewed);
      return s;
    }
    Stopwatch sw;
    voxel_.filter(sweep, map_points);
    const localization::GicpOdometryOutput out = gicp_->process(map_points);
    return {out.T_world_lidar, sw.elapsed_ms(), 0.0, out.healthy, false};
  }

 private:
  std::optional<localization::Loam> loam_;
  std::optional<localization::GicpOdometry> gicp_;
  perception::VoxelGrid voxel_;
};

}  // namespace

RecordedOdometryResult run_recorded_odometry(const SweepSequence& seq, const RecordedOdometryOptions& o) {
  o.validate();
  if (seq.count == 0 || !seq.read) throw Error("odometry: the recording holds no sweeps");
  if (!seq.truth.empty() && seq.truth.size() < seq.count)
    throw Error("odometry: " + std::to_string(seq.truth.size()) + " reference poses for " + std::to_string(seq.count) +
                " sweeps (expected one per sweep)");
  const perception::LidarModel model = perception::lidar_model(o.lidar);
  const std::size_t n = o.max_sweeps > 0 ? std::min(o.max_sweeps, seq.count) : seq.count;
  RecordedOdometryResult r;
  if (!seq.truth.empty()) r.truth.assign(seq.truth.begin(), seq.truth.begin() + static_cast<std::ptrdiff_t>(n));
  OdometryMethod method(o, r.truth.empty() ? SE3::Identity() : r.truth.front());
  MapAccumulator map(o.map_voxel_m);
  ProgressBar bar("odometry", n, o.progress);
  PointCloud map_points;
  for (std::size_t i = 0; i < n; ++i) {
    PointCloud sweep = seq.read(i);
    r.points += sweep.size();
    Stopwatch pre;
    const perception::RingReconstruction rings = perception::reconstruct_rings(sweep, model);
    sweep.rings = rings.rings;
    r.ring_method = rings.method;
    r.ring_count = rings.ring_count;
    if (o.deskew && !sweep.has_time() && !sweep.empty()) {
      sweep.time_offsets_s = perception::times_from_azimuth(sweep, 1.0 / model.rate_hz, model.clockwise);
      r.times_from_azimuth = true;
    }
    r.preprocess_ms.push_back(pre.elapsed_ms());
    const double cpu0 = thread_cpu_ms();
    const MethodStep s = method.step(sweep, map_points);
    r.method_cpu_ms.push_back(thread_cpu_ms() - cpu0);
    r.method_ms.push_back(s.ms);
    r.mapping_ms.push_back(s.mapping_ms);
    r.unhealthy += s.healthy ? 0 : 1;
    r.degenerate += s.degenerate ? 1 : 0;
    r.estimate.push_back(s.T_world_lidar);
    r.stamps_s.push_back(sweep.stamp_s > 0.0 ? sweep.stamp_s : static_cast<double>(i) / model.rate_hz);
    map.add(map_points, s.T_world_lidar);
    bar.update(i + 1);
  }
  bar.finish();
  r.map = map.take();
  return r;
}

std::vector<SE3> direct_registration_trajectory(const SweepSequence& seq, double voxel_m, double min_range_m) {
  if (seq.count == 0 || !seq.read) throw Error("direct_registration_trajectory: no sweeps");
  perception::VoxelGridParams vp;
  vp.leaf_size_m = Eigen::Vector3d::Constant(voxel_m);
  const localization::GicpParams p{
      .max_iterations = 200, .converged_translation_m = 1e-5, .converged_rotation_rad = 1e-6};
  const auto load = [&](std::size_t i) {
    const PointCloud raw = seq.read(i);
    PointCloud kept;
    for (const Eigen::Vector3f& q : raw.points)
      if (q.allFinite() && q.norm() > min_range_m) kept.points.push_back(q);
    return localization::prepare_gicp_cloud(perception::voxel_downsample(kept, vp), p);
  };
  const localization::GicpCloud first = load(0);
  std::vector<SE3> T{SE3::Identity()};
  for (std::size_t i = 1; i < seq.count; ++i) {
    const SE3 guess = i < 2 ? SE3::Identity() : T.back() * T[i - 2].inverse() * T.back();
    T.push_back(localization::gicp_align(load(i), first, guess, p).T_target_source);
  }
  return T;
}

TrajectoryEvaluation evaluate_trajectory(const std::vector<SE3>& truth, const std::vector<SE3>& estimate,
                                         double rpe_distance_m) {
  TrajectoryEvaluation e;
  const std::vector<double> d = localization::path_distances(truth);
  e.distance_m = d.empty() ? 0.0 : d.back();
  e.end_point_error_m = localization::end_point_error_m(truth, estimate);
  e.ate = localization::absolute_trajectory_error(truth, estimate);
  e.rpe_frame = localization::relative_pose_error(truth, estimate, 1);
  e.rpe_distance_m = rpe_distance_m;
  e.rpe_distance = localization::relative_pose_error_at_distance(truth, estimate, rpe_distance_m);
  e.kitti = localization::kitti_relative_error(truth, estimate);
  const std::vector<double> lengths = localization::whole_metre_lengths(truth);
  if (!lengths.empty())
    e.kitti_short = localization::kitti_relative_error(truth, estimate, {lengths, e.kitti_short_step_frames});
  return e;
}

}  // namespace bipednav::runner
