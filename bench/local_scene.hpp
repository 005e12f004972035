#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/common/path.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/planning/local/teb_params.hpp"

namespace bipednav::bench {

// A reproducible local-planning scene: an 8 x 8 m, 0.05 m costmap centred on the robot with
// n_obstacles small round obstacles (lethal core, inscribed ring) scattered by a seeded RNG, and a
// straight global plan across the window.
struct LocalBenchScene {
  mapping::Costmap2D costmap;
  Path plan;
  Pose2 start;
};
LocalBenchScene make_local_bench_scene(int n_obstacles, std::uint64_t seed);

// Marks the cells whose centre lies within r of (x, y) lethal and those within r + inscribed_m
// inscribed (a round obstacle with its inscribed ring).
void stamp_disc(mapping::Costmap2D& costmap, double x, double y, double r, double inscribed_m);

// Cycle times of the TEB planner driving a simulated unicycle through a scene.
struct LocalBenchStats {
  int obstacles = 0;  // obstacles extracted from the costmap
  int cycles = 0;
  double median_ms = 0.0;
  double p99_ms = 0.0;
  double max_ms = 0.0;
  double cpu_median_ms = 0.0;  // CPU time of the calling thread (robust on a loaded machine)
  double cpu_p99_ms = 0.0;
  int success_cycles = 0;
};
LocalBenchStats run_local_bench(const LocalBenchScene& scene, const planning::local::TebParams& params, int cycles);

}  // namespace bipednav::bench
