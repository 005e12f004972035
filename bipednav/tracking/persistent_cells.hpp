#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <unordered_map>

namespace bipednav::tracking {

// The static part of what the sensors see, learnt from the obstacle points themselves: a cell
// (square, cell_m) hit in cycle after cycle, never unhit for longer than max_gap_s, for at least
// min_span_s is persistent, and stays so until it has gone unhit for memory_s. A mover covers a
// cell only while it passes (a 0.5 m object at 0.3 m/s: 2 s); a wall, a post or a box keeps its
// cells hit whenever it is in view. Unlike the global map's lethal cells, the evidence survives
// the map's ray clearing over obstacles lower than a LiDAR and the parts of an object a sensor
// sees only now and then.
class PersistentCells {
 public:
  PersistentCells(double cell_m, double min_span_s, double max_gap_s, double memory_s);

  // One cycle's points (x, y used) at stamp_s (times that do not advance are ignored); a point
  // for which skip(point) is true adds no evidence (e.g. one on a known mover).
  template <typename Skip>
  void add(std::span<const Eigen::Vector3d> points, double stamp_s, Skip skip) {
    if (!(stamp_s > stamp_s_)) return;
    stamp_s_ = stamp_s;
    for (const auto& p : points)
      if (p.allFinite() && !skip(p)) hit(p, stamp_s);
    forget_old(stamp_s);
  }
  // Whether the cell of p is persistent as of the latest cycle.
  bool persistent(const Eigen::Vector2d& p) const;
  void clear();
  std::size_t cells() const { return cells_.size(); }

 private:
  struct Run {
    double start_s = 0.0;  // when the current run of hits began
    double last_s = 0.0;   // the latest hit
    bool earned = false;   // the run has lasted min_span_s
  };
  void hit(const Eigen::Vector3d& p, double stamp_s);
  void forget_old(double stamp_s);
  bool key_of(const Eigen::Vector2d& p, std::uint64_t& key) const;

  double cell_m_, min_span_s_, max_gap_s_, memory_s_;
  std::unordered_map<std::uint64_t, Run> cells_;
  double stamp_s_ = -1e300, last_forget_s_ = -1e300;
};

}  // namespace bipednav::tracking
