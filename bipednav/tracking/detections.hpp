#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/tracking/detection.hpp"
#include "bipednav/tracking/persistent_cells.hpp"
#include "bipednav/tracking/static_structure.hpp"
#include "bipednav/tracking/tracker_params.hpp"

namespace bipednav::tracking {

// One sensor cycle's input to the tracker: the obstacle points (not ground) of the cycle in the
// map frame, their heights above the floor, the robot's pose when they were seen (the sensors'
// viewpoint, and where the visibility model looks from) and the time.
struct DetectionInput {
  double stamp_s = 0.0;
  Pose2 T_map_base;
  std::span<const Eigen::Vector2d> points_map;
  std::span<const double> heights_m;  // empty (unknown) or one per point
};

// The finite points of `in` within max_range_m of the robot as (x, y, height); an unknown height
// is 0. Throws Error when heights_m is neither empty nor one per point.
std::vector<Eigen::Vector3d> points_in_range(const DetectionInput& in, const TrackerParams& params);

// Where a proven mover is predicted: no static map explains the points in it (the cells a
// person stands on turn lethal in a map, and long-standing if they wait).
struct MoverCircle {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
  bool contains(const Eigen::Vector2d& p) const { return (p - center).squaredNorm() <= radius_m * radius_m; }
};

// The points the static map does not explain: in a mover circle, or else neither within
// static_margin_m of a cell of `static_cells` lethal for static_age_s nor on a cell `persistent`
// (may be null) holds.
std::vector<Eigen::Vector3d> unexplained_points(std::span<const Eigen::Vector3d> points,
                                                const StaticStructure& static_cells, const PersistentCells* persistent,
                                                std::span<const MoverCircle> movers, const TrackerParams& params);

// The detections of the unexplained points: clustered (euclidean_clusters) and measured
// (measure_cluster) from `viewpoint`; clusters wider than max_cluster_radius_m are left out.
std::vector<Detection> detect_objects(std::span<const Eigen::Vector3d> unexplained, const Eigen::Vector2d& viewpoint,
                                      const TrackerParams& params, bool heights_known = true);

}  // namespace bipednav::tracking
