#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "bipednav/common/point_cloud.hpp"

namespace bipednav::localization {

// Feature extraction of LOAM (section 4.4.1).
struct FeatureParams {
  int neighbours_per_side = 5;      // |S| = 2 * this (eq. 4.5)
  int sub_regions = 4;              // identical sub-regions per ring
  int max_edges_per_region = 2;     // sharp edge points used by odometry
  int max_planars_per_region = 4;   // flat planar points used by odometry
  int map_feature_factor = 10;      // the mapping / reference sets hold this many times more
  double edge_threshold = 0.01;     // smoothness (eq. 4.5) above which a point is an edge
  double planar_threshold = 0.005;  // smoothness below which a point is planar
  double min_range_m = 0.3;
  double max_range_m = 100.0;
  double occlusion_ratio = 0.1;                    // relative depth jump that marks an occlusion boundary
  double parallel_beam_ratio = 0.02;               // neighbour gap / range above which the surface is grazing
  double max_neighbour_gap_ratio = 0.1;            // gap / range that breaks a ring into separate segments
  int rings = 16;                                  // used only to derive rings when the cloud has none
  double min_elevation_rad = -0.2617993877991494;  // VLP-16: -15 deg
  double max_elevation_rad = 0.2617993877991494;   // VLP-16: +15 deg
  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("neighbours_per_side", neighbours_per_side);
    v("sub_regions", sub_regions);
    v("max_edges_per_region", max_edges_per_region);
    v("max_planars_per_region", max_planars_per_region);
    v("map_feature_factor", map_feature_factor);
    v("edge_threshold", edge_threshold);
    v("planar_threshold", planar_threshold);
    v("min_range_m", min_range_m);
    v("max_range_m", max_range_m);
    v("occlusion_ratio", occlusion_ratio);
    v("parallel_beam_ratio", parallel_beam_ratio);
    v("max_neighbour_gap_ratio", max_neighbour_gap_ratio);
    v("rings", rings);
    v("min_elevation_rad", min_elevation_rad);
    v("max_elevation_rad", max_elevation_rad);
  }
};

// Edge and planar points of one sweep. Each set is a PointCloud carrying the points' time offsets
// and rings. The odometry sets are subsets of the map sets.
struct LoamFeatures {
  PointCloud edges;      // E_{k+1}: sharpest points (max_edges_per_region per sub-region)
  PointCloud planars;    // H_{k+1}: flattest points
  PointCloud map_edges;  // map_feature_factor times more, for the reference sweep and mapping
  PointCloud map_planars;
  std::size_t total_features() const { return edges.size() + planars.size(); }
};

// Smoothness of eq. 4.5 for each point of one ring ordered by firing time; points with fewer than
// `k` neighbours on either side get -1.
std::vector<double> ring_smoothness(const std::vector<Eigen::Vector3f>& ring, int k);

// Drops non-finite points and points outside [min_range_m, max_range_m], keeping the other fields.
PointCloud sanitize_sweep(const PointCloud& sweep, const FeatureParams& p);
// sanitize_sweep's result without a copy when it keeps every point: `sweep` itself, else `storage`
// filled with sanitize_sweep(sweep, p) (a simulated sweep often has nothing to drop).
const PointCloud& sanitized(const PointCloud& sweep, const FeatureParams& p, PointCloud& storage);

// Ring index per point: the cloud's own rings, else derived from the elevation angle.
std::vector<std::uint16_t> ring_indices(const PointCloud& sweep, const FeatureParams& p);

// extract_features' work space, kept between rings and sweeps by its owner (extract_features runs
// ~16 rings of ~1000 points per sweep: allocating these per ring cost more than some of the work
// done in them). What it held does not change the features.
struct FeatureScratch {
  // The ranges of one ring's points and the gaps between neighbours (gap[i] = |p[i+1] - p[i]|),
  // computed once: the marking reads each several times.
  struct RingGeometry {
    std::vector<float> range, gap;
    void assign(const std::vector<Eigen::Vector3f>& pts);
  };
  std::vector<std::uint32_t> order;  // the sweep's point indices grouped by ring
  std::vector<std::size_t> ring_begin, next;
  std::vector<float> azimuth;  // the sort key of clouds without times
  std::vector<std::uint16_t> derived_rings;
  std::vector<Eigen::Vector3f> pts;
  std::vector<Eigen::Vector3d> prefix;
  std::vector<double> c;
  std::vector<char> picked;
  RingGeometry ring;
  std::vector<int> sharp, flat;
  std::vector<std::pair<double, int>> scored;
  std::vector<std::uint64_t> packed;
};

// Extracts the features of a sanitized sweep: points are grouped per ring, ordered by time offset
// (azimuth when the cloud has no times), scored with eq. 4.5 and selected per sub-region. Without
// `scratch` the call allocates its own.
LoamFeatures extract_features(const PointCloud& sweep, const FeatureParams& p, FeatureScratch* scratch = nullptr);

}  // namespace bipednav::localization
