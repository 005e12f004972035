#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "bipednav/mapping/cell_rect.hpp"
#include "bipednav/mapping/costmap2d.hpp"

namespace bipednav::mapping {

// One sensor's returns for a costmap update: points already filtered to obstacle heights, all in
// the map frame, and the sensor's origin (map frame) from which rays are traced for clearing.
struct Observation {
  Eigen::Vector3d origin_map = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3f> points_map;
  double max_range_m = 1e9;  // the sensor's own range: returns farther than this are ignored
  bool marking = true;
  bool clearing = true;
};

struct ObstacleLayerParams {
  double obstacle_max_range_m = 4.0;  // mark only returns closer than this (3D distance to the origin)
  double raytrace_max_range_m = 5.0;  // clear along rays at most this long (longer rays are clipped)

  void validate() const;
};

// Marking and ray-trace clearing on a three-state grid (kUnknown = never seen, kFree = seen free,
// kLethal = obstacle). All rays of all observations clear first, then all returns mark, so one
// observation cannot erase another's obstacles of the same update. A clearing ray frees the cells
// from the sensor to the return, not the return's own cell; a ray longer than the raytrace range
// (or leaving the grid) is clipped and frees its whole clipped length. Returns outside the grid,
// beyond the ranges, or with a NaN coordinate are ignored.
class ObstacleLayer {
 public:
  explicit ObstacleLayer(const ObstacleLayerParams& params = {});

  // Applies the observations to `grid`; returns the bounding box of the cells whose value changed.
  // With `allow_clearing` false no observation clears (marking only).
  CellRect update(Costmap2D& grid, const std::vector<Observation>& observations, bool allow_clearing = true);

  const ObstacleLayerParams& params() const { return params_; }

 private:
  void clear_observation(Costmap2D& grid, const Observation& obs, CellRect& changed);
  void mark_observation(Costmap2D& grid, const Observation& obs, CellRect& changed) const;

  ObstacleLayerParams params_;
  std::vector<std::uint32_t> traced_;  // per cell: stamp of the last observation that traced a ray to it
  std::uint32_t stamp_ = 0;
};

}  // namespace bipednav::mapping
