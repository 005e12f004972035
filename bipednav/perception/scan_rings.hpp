#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/perception/lidar_model.hpp"

namespace bipednav::perception {

// The ring (laser index) of each point of a sweep recorded without one. LOAM's smoothness
// (eq. 4.5) compares neighbours along one laser's scan line, so every point needs its line.

// Nearest beam of `elevations_rad` (ascending) to the point's elevation atan2(z, hypot(x, y)).
// Exact where the beams leave from the sensor origin (VLP-16, HDL-32E, Ouster: offsets of a few mm).
std::vector<std::uint16_t> rings_from_beam_table(const PointCloud& sweep, const std::vector<double>& elevations_rad);

// Scan-line order: the sweep is stored line after line, each line one revolution in azimuth
// (KITTI's HDL-64E sweeps: each line runs counter-clockwise from behind the sensor, -pi, to +pi).
// The lines' direction is the sign most consecutive azimuth steps have; a new line starts where
// the azimuth wraps against it by more than pi, once the current line holds at least
// `min_line_points` (points at the seam jitter across it, giving wraps a point apart). Lines are
// numbered in stream order; `lines` receives their count.
std::vector<std::uint16_t> rings_from_scan_order(const PointCloud& sweep, std::size_t min_line_points,
                                                 std::size_t& lines);

// Clusters of the measured elevations: the optimal 1D k-means (k = `beams`) of a histogram of
// 0.01 deg bins, found exactly by dynamic programming (no start values, so a unit whose beams sit
// off the nominal table, by calibration, still gets one cluster per beam); ring 0 is the lowest.
// For a sensor whose table is only nominal and whose points are not stored line by line. Beams
// leaving from points offset from the origin (the HDL-64E's two blocks) spread each cluster by
// offset / range: close points may join a neighbouring beam.
std::vector<std::uint16_t> rings_from_elevation_clusters(const PointCloud& sweep, std::size_t beams);

enum class RingMethod { from_cloud, beam_table, scan_order, elevation_clusters };
std::string to_string(RingMethod m);

struct RingReconstruction {
  std::vector<std::uint16_t> rings;
  RingMethod method = RingMethod::from_cloud;
  std::size_t ring_count = 0;  // distinct ring values used (max + 1)
};

// The cloud's own rings when it has them; else the beam table when model.table_assigns_rings;
// else the scan-line order when it finds between 0.9 and 1.1 times the model's beams (plus one,
// for a sweep that starts mid-line), each line at least a quarter of the average line's points;
// else elevation clusters.
RingReconstruction reconstruct_rings(const PointCloud& sweep, const LidarModel& model);

}  // namespace bipednav::perception
