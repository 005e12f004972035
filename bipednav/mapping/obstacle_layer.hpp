#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <limits>
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
  // Keep the heights the returns were seen at (height-aware clearing, see ObstacleLayer). Off for
  // moving obstacles: a walker seen only at leg height by a depth camera must be cleared by the
  // LiDAR rays that cross its old cells higher up, or it leaves a trail.
  bool keep_heights = true;
};

struct ObstacleLayerParams {
  double obstacle_max_range_m = 4.0;  // mark only returns closer than this (3D distance to the origin)
  double raytrace_max_range_m = 5.0;  // clear along rays at most this long (longer rays are clipped)
  // Keep each obstacle cell's band of seen heights and let a ray clear it only where it crosses
  // that band (see ObstacleLayer). It keeps low obstacles the LiDAR passes over (turtlebot3_world's
  // 0.5 m cylinders), but also low false marks only a depth camera can clear: use it with decay.
  bool height_aware_clearing = false;
  // Mark decay (as the spatio-temporal voxel layer's decay inside the sensors' view): an obstacle
  // cell that rays have passed (over or under its band) in more than this many updates since a
  // return last confirmed it goes back to unknown. 0: marks never expire. Only with
  // height_aware_clearing does a ray pass a mark without clearing it, so only then can a mark decay.
  int mark_lifetime_updates = 0;

  void validate() const;
};

// A decay time as a count of updates at `rate_hz` (at least one when decay_s > 0; 0: no decay).
int decay_updates(double decay_s, double rate_hz);

// The heights (map frame) at which the returns that marked a cell were seen; empty = not known.
struct HeightBand {
  float lo = std::numeric_limits<float>::infinity();
  float hi = -std::numeric_limits<float>::infinity();

  bool empty() const { return lo > hi; }
  void include(float z) {
    lo = std::min(lo, z);
    hi = std::max(hi, z);
  }
  void include(const HeightBand& b) {
    lo = std::min(lo, b.lo);
    hi = std::max(hi, b.hi);
  }
};

// Marking and ray-trace clearing on a three-state grid (kUnknown = never seen, kFree = seen free,
// kLethal = obstacle). All rays of all observations clear first, then all returns mark, so one
// observation cannot erase another's obstacles of the same update. A clearing ray frees the cells
// from the sensor to the return, not the return's own cell; a ray longer than the raytrace range
// (or leaving the grid) is clipped and frees its whole clipped length. Returns outside the grid,
// beyond the ranges, or with a NaN coordinate are ignored.
//
// With height_aware_clearing (a 2.5D voxel layer), each obstacle cell keeps the band of heights its
// returns were seen at, and a ray frees it only where the ray crosses the cell within that band.
// A LiDAR ray passing over a 0.5 m cylinder seen by a depth camera says nothing about the
// cylinder, and a plain 2D ray trace would erase it. Obstacle cells with no known band (set by
// someone else) are freed by any ray, as in 2D.
//
// Rays that cross a band are the sensors' negative evidence (a depth camera's ground returns cross
// the low marks in its frustum). Rays that pass a mark over or under its band are weaker evidence:
// the sensor looked at that spot and a real obstacle there would have to hide outside the sensor's
// heights. A false low mark (a wall's foot seen a cell off by a localization error) is passed over
// by every LiDAR sweep and crossed low by nothing; a 0.5 m cylinder looks the same to the LiDAR.
// So, with mark_lifetime_updates > 0, such passes count against a mark: once more than
// mark_lifetime_updates updates have passed it since a return (or include_band) last confirmed
// it, it goes back to kUnknown. A cylinder the depth cameras keep seeing stays; one they
// no longer look at is kept that long (the route it forced stays while the robot turns away). A
// mark that no ray passes (out of every sensor's view: behind a wall, out of range) does not age:
// no sensor could have confirmed it, so its absence of returns says nothing. That is what lets the
// global map's own LiDAR marks decay too: a wall the LiDAR sees is confirmed by every sweep, a wall
// it cannot see is kept, and only a mark the LiDAR looks at and no sensor confirms goes. Obstacle
// cells set by someone else (a prior map) have no mark and never expire. Marks are not told apart
// by the sensor that made them: a depth camera's mark the LiDAR passes over ages exactly as a LiDAR
// mark it passes; a shorter lifetime for camera marks would encode which sensor is more often
// wrong, not what the rays saw.
class ObstacleLayer {
 public:
  explicit ObstacleLayer(const ObstacleLayerParams& params = {});

  // Applies the observations to `grid`; returns the bounding box of the cells whose value changed.
  // With `allow_clearing` false no observation clears (marking only), and no mark ages.
  CellRect update(Costmap2D& grid, const std::vector<Observation>& observations, bool allow_clearing = true);

  const ObstacleLayerParams& params() const { return params_; }

  // The height band of cell (x, y) of the grid last updated (empty when unknown).
  const HeightBand& band(int x, int y) const;
  // Widens cell (x, y)'s band: obstacles copied into the grid from elsewhere keep their heights.
  // With `reset` the cell's old band is dropped first (the cell was not an obstacle before).
  // The mark counts as confirmed `used` of its lifetime ago (0: now, 1: a whole lifetime; see
  // mark_lifetime_updates): a mark copied from another layer keeps the age it had there. An older
  // `used` never makes an existing mark older, and an obstacle someone else set (a prior map's
  // wall) stays permanent. Without height_aware_clearing no bands are kept (band() is always
  // empty); without either option this does nothing.
  void include_band(const Costmap2D& grid, int x, int y, const HeightBand& b, bool reset, double used = 0.0);
  // Whether marks (height bands, confirmation ages) are kept at all: with neither option there is
  // nothing to keep, and include_band does nothing.
  bool keeps_marks() const { return params_.height_aware_clearing || params_.mark_lifetime_updates > 0; }
  // Every mark forgotten (cells no longer expire): the grid was replaced from elsewhere.
  void forget_marks();
  // Updates in which rays passed the mark of cell (x, y) since a return last confirmed it; -1 when
  // the cell has no expiring mark.
  int mark_age(int x, int y) const;

 private:
  // What the layer keeps of an obstacle cell: its heights, and for decay the updates that passed
  // it unconfirmed (-1: the mark does not expire) and the last update counted.
  struct Mark {
    HeightBand band;
    std::int32_t passes = -1;
    std::uint32_t counted = 0;
  };

  void follow(const Costmap2D& grid);  // marks follow the grid's size and rolling-window moves
  void clear_observation(Costmap2D& grid, const Observation& obs, CellRect& changed);
  void mark_observation(Costmap2D& grid, const Observation& obs, CellRect& changed);
  void expire(Costmap2D& grid, CellRect& changed);

  ObstacleLayerParams params_;
  GridGeometry band_geometry_;
  std::vector<Mark> marks_;            // per cell of band_geometry_
  std::uint32_t tick_ = 0;             // updates so far (1, 2, ...; 0: none)
  std::vector<std::uint32_t> traced_;  // per cell: stamp of the last observation that traced a ray to it
  std::uint32_t stamp_ = 0;
  std::vector<std::int32_t> codes_;  // per point of an observation: its cell (see RayClipper::end_cells)
};

}  // namespace bipednav::mapping
