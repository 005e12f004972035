#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <vector>

#include "bipednav/tracking/detection.hpp"
#include "bipednav/tracking/tracker_params.hpp"

namespace bipednav::tracking {

// The measurement of one cluster (the points `members` of `points`: x, y in the map frame, z the
// height above the floor) seen from `viewpoint`. A range sensor sees the near side of an object,
// so the points' centroid lies short of its centre by up to its half depth (a 0.25 m radius
// cylinder: pi/4 r = 0.2 m, twice the tracker's accuracy goal). The centre is placed instead on
// the line of sight through the middle of the points' lateral extent, at the near surface (the
// median range of the points within the middle quarter of that extent) plus the half width: exact
// for a circle, a square face-on and a square corner-on. Its covariance (TrackerParams): the
// point noise, plus shape_noise_ratio times the half width along the line of sight, plus
// lateral_noise_ratio times it across.
// `heights_known`: the points' z are heights (else Detection::height_span_m is -1).
Detection measure_cluster(std::span<const Eigen::Vector3d> points, const std::vector<std::size_t>& members,
                          const Eigen::Vector2d& viewpoint, const TrackerParams& params, bool heights_known = true);

}  // namespace bipednav::tracking
