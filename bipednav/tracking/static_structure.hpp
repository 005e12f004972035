#pragma once

#include <Eigen/Core>
#include <vector>

#include "bipednav/mapping/costmap2d.hpp"

namespace bipednav::tracking {

// Long-standing obstacles of an occupancy grid (kLethal cells, e.g. the global map's occupancy):
// for every cell, since when it has been lethal without interruption, as of the latest update;
// and the latest spell in which it was free (kFree at every update).
// With a gap allowance an interruption up to max_gap_s long does not count (a wall cell that the
// map's ray clearing empties now and then stays long-standing).
class StaticStructure {
 public:
  // The occupancy at stamp_s (times that do not advance are ignored). A grid of another geometry
  // starts over.
  void update(const mapping::Costmap2D& occupancy, double stamp_s, double max_gap_s = 0.0);
  void clear();
  bool empty() const { return since_.empty(); }
  // Whether a cell within margin_m of p (map frame) had been lethal for at least min_age_s at the
  // latest update.
  bool near(const Eigen::Vector2d& p, double margin_m, double min_age_s) const;
  // Whether the cell at p was free without interruption for min_span_s, that spell lasting until
  // within_s of the latest update.
  bool was_free(const Eigen::Vector2d& p, double min_span_s, double within_s) const;

 private:
  mapping::GridGeometry geometry_;
  std::vector<double> since_;                   // +infinity: not lethal
  std::vector<double> last_;                    // when last lethal (with a gap allowance)
  std::vector<double> free_since_, free_last_;  // the latest free spell of each cell
  double stamp_s_ = -1e300;
};

}  // namespace bipednav::tracking
