#include "bipednav/perception/pipeline.hpp"

#include <cmath>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/perception/deskew.hpp"

namespace bipednav::perception {

void PerceptionParams::validate() const {
  depth_voxel.validate();
  ransac.validate();
  require(depth_decimation >= 1 && depth_decimation <= 8, "depth_decimation", "in [1, 8] (1 = off)");
  require(depth_image_width >= 1, "depth_image_width", ">= 1 pixel");
  require(depth_max_range_m > 0.0, "depth_max_range_m", "> 0 m");
  require(lidar_min_range_m >= 0.0 && lidar_min_range_m < lidar_max_range_m, "lidar_min_range_m",
          ">= 0 and < lidar_max_range_m");
  require(lidar_voxel_m >= 0.0 && std::isfinite(lidar_voxel_m), "lidar_voxel_m", ">= 0 m (0 disables)");
  require(prior_ground.allFinite() && prior_ground.head<3>().norm() > 1e-9, "prior_ground",
          "a finite plane [a, b, c, d] with a non-zero normal");
  require(max_ground_offset_m >= 0.0, "max_ground_offset_m", ">= 0 m");
  require(min_ground_inliers >= 3, "min_ground_inliers", ">= 3");
  require(min_obstacle_height_m >= 0.0, "min_obstacle_height_m", ">= 0 m");
  require(obstacle_height_margin_m >= 0.0, "obstacle_height_margin_m", ">= 0 m");
}

PerceptionPipeline::PerceptionPipeline(PerceptionParams params)
    : params_((params.validate(), std::move(params))), rng_(params_.seed), depth_voxel_(params_.depth_voxel) {
  params_.prior_ground = normalize_plane(params_.prior_ground);
}

void PerceptionPipeline::add_depth(FusedCloud& fused, const DepthCloud& depth, const RobotProfile& robot,
                                   PerceptionOutput& out) {
  const SensorMount* mount = robot.sensor(depth.camera);
  if (!mount)
    throw Error("perception: depth cloud from camera '" + depth.camera + "', which robot profile '" + robot.name +
                "' does not mount");
  const auto width = static_cast<std::size_t>(params_.depth_image_width);
  const PointCloud& cloud = depth.cloud;
  if (params_.depth_decimation > 1 && !cloud.empty() && cloud.size() % width == 0) {
    // Decimation and the range limit in one pass (the same points as decimating, then cropping);
    // range first (section 4.2.2), then the voxel grid (4.2.1): the far, sparse points that the
    // range limit drops would each fill a voxel of their own.
    const DecimationCounts n = decimate_depth_within(cloud, params_.depth_image_width, params_.depth_decimation,
                                                     params_.depth_max_range_m, decimated_);
    out.depth_points_in += n.finite;
    out.depth_points_decimated += n.blocks;
    depth_voxel_.filter(decimated_, voxels_);
  } else {  // not decimated (off, or not an organised cloud of this width): every point goes on
    for (const auto& p : cloud.points) out.depth_points_in += p.allFinite() ? 1u : 0u;
    out.depth_points_decimated += cloud.size();
    PassThroughParams range;
    range.max_range_m = params_.depth_max_range_m;
    const PassThroughTest crop(range);
    depth_voxel_.filter(cloud, voxels_, &crop);
  }
  out.depth_points_voxel += voxels_.size();
  append_sensor_cloud(fused, voxels_, mount->T_base_sensor(), mount->name, params_.depth_max_range_m);
}

void PerceptionPipeline::add_lidar(FusedCloud& fused, const PointCloud& raw, const PerceptionInput& in,
                                   const RobotProfile& robot) {
  const SensorMount* mount = robot.lidar();
  if (!mount) throw Error("perception: a LiDAR sweep arrived but robot profile '" + robot.name + "' mounts no vlp16");
  const PointCloud& sweep =
      params_.deskew_lidar && deskew_sweep(raw, mount->T_base_sensor(), in.base_velocity, in.stamp_s, lidar_deskewed_)
          ? lidar_deskewed_
          : raw;
  PassThroughParams range;
  range.min_range_m = params_.lidar_min_range_m;
  range.max_range_m = params_.lidar_max_range_m;
  const PassThroughTest crop(range);
  if (params_.lidar_voxel_m > 0.0) {
    VoxelGridParams v;
    v.leaf_size_m.setConstant(params_.lidar_voxel_m);
    VoxelGrid(v).filter(sweep, lidar_kept_, &crop);
    append_sensor_cloud(fused, lidar_kept_, mount->T_base_sensor(), mount->name, params_.lidar_max_range_m);
    return;
  }
  // The range filter while fusing: no copy of the sweep (with its time offsets and rings).
  append_sensor_cloud(fused, sweep, mount->T_base_sensor(), mount->name, params_.lidar_max_range_m, &crop);
}

void PerceptionPipeline::choose_plane(const PlaneFit& fit, PerceptionOutput& out) const {
  const Plane& prior = params_.prior_ground;
  // Height of each plane below/above the base origin along the prior's normal: d / (n . n_prior).
  const double cos_angle = fit.plane.head<3>().dot(prior.head<3>());
  const bool near_prior =
      cos_angle > 1e-6 && std::fabs(fit.plane[3] / cos_angle - prior[3]) <= params_.max_ground_offset_m;
  out.plane_from_ransac = fit.found && fit.inliers >= params_.min_ground_inliers && near_prior;
  out.ground_plane = out.plane_from_ransac ? fit.plane : prior;
}

void PerceptionPipeline::classify(const FusedCloud& fused, double robot_height_m, PerceptionOutput& out) const {
  const Eigen::Vector4f pl = out.ground_plane.cast<float>();
  const auto t = static_cast<float>(params_.ransac.distance_threshold_m);
  const auto h_min = static_cast<float>(params_.min_obstacle_height_m);
  const auto h_max = static_cast<float>(robot_height_m + params_.obstacle_height_margin_m);
  // Written in place (room for every point, trimmed after): the points appended in order.
  const std::size_t n = fused.size();
  const std::size_t g0 = out.ground.size(), gs0 = out.ground_source.size();
  const std::size_t o0 = out.obstacles.size(), os0 = out.obstacle_source.size();
  out.ground.points.resize(g0 + n);
  out.ground_source.resize(gs0 + n);
  out.obstacles.points.resize(o0 + n);
  out.obstacle_source.resize(os0 + n);
  std::size_t g = 0, o = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3f& p = fused.cloud.points[i];
    const float h = signed_distance(pl, p);
    if (std::fabs(h) < t) {
      out.ground.points[g0 + g] = p;
      out.ground_source[gs0 + g++] = fused.source[i];
    } else if (h >= h_min && h <= h_max) {
      out.obstacles.points[o0 + o] = p;
      out.obstacle_source[os0 + o++] = fused.source[i];
    }
  }
  out.ground.points.resize(g0 + g);
  out.ground_source.resize(gs0 + g);
  out.obstacles.points.resize(o0 + o);
  out.obstacle_source.resize(os0 + o);
  out.ground_inliers = out.ground.size();
}

PerceptionOutput PerceptionPipeline::process(const SensorFrame& frame, const RobotProfile& robot) {
  PerceptionInput in;
  in.stamp_s = frame.stamp_s;
  in.lidar = frame.lidar ? &*frame.lidar : nullptr;
  for (const DepthCloud& d : frame.depth) in.depth.push_back(&d);
  PerceptionOutput out;
  process(in, robot, out);
  return out;
}

void PerceptionPipeline::process(const PerceptionInput& in, const RobotProfile& robot, PerceptionOutput& out) {
  const Stopwatch total;
  for (PointCloud* c : {&out.obstacles, &out.ground}) {
    c->clear();
    c->frame_id = "base_link";
    c->stamp_s = in.stamp_s;
  }
  out.obstacle_source.clear();
  out.ground_source.clear();
  out.ground_plane = ground_plane_z0();
  out.plane_from_ransac = false;
  out.ground_inliers = out.depth_points_in = out.depth_points_decimated = out.depth_points_voxel = 0;
  out.timings = {};
  FusedCloud& fused = fused_;
  fused.cloud.clear();
  fused.source.clear();
  fused.sources.clear();
  Stopwatch sw;
  for (const DepthCloud* d : in.depth)
    if (d) add_depth(fused, *d, robot, out);
  out.timings.depth_ms = sw.elapsed_ms();
  sw.restart();
  if (in.lidar) add_lidar(fused, *in.lidar, in, robot);
  out.timings.lidar_ms = sw.elapsed_ms();
  sw.restart();
  RansacParams ransac = params_.ransac;
  ransac.prior_normal = params_.prior_ground.head<3>();
  ransac.inlier_std = false;  // choose_plane reads the plane and its inlier count only
  const PlaneFit fit = fit_plane_ransac(fused.cloud.points, ransac, rng_, &ransac_scratch_);  // section 4.3
  choose_plane(fit, out);
  out.timings.segmentation_ms = sw.elapsed_ms();
  sw.restart();
  classify(fused, robot.height_m, out);
  out.sources = fused.sources;
  out.timings.classification_ms = sw.elapsed_ms();
  out.timings.total_ms = total.elapsed_ms();
}

}  // namespace bipednav::perception
