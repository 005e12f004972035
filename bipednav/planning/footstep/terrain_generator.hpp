#pragma once

#include <cstdint>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/mapping/heightmap.hpp"
#include "bipednav/planning/footstep/footstep_planner.hpp"

namespace bipednav::planning::footstep {

// Random cluttered heightmaps like those of the second reference's Table I: a flat floor with
// bars (low and thin: stepped over), platforms (low and wide: stepped onto) and blocks (tall:
// walked around), each a rotated box.
struct TerrainGeneratorParams {
  double size_m = 2.5;
  double resolution_m = 0.004;
  int bars = 3, platforms = 3, blocks = 4;
  double bar_height_min_m = 0.02, bar_height_max_m = 0.05;
  double bar_width_min_m = 0.02, bar_width_max_m = 0.05;
  double bar_length_min_m = 0.6, bar_length_max_m = 2.0;
  double platform_height_min_m = 0.02, platform_height_max_m = 0.06;
  double platform_size_min_m = 0.35, platform_size_max_m = 0.8;
  double block_height_min_m = 0.15, block_height_max_m = 0.5;
  double block_size_min_m = 0.08, block_size_max_m = 0.35;

  void validate() const;
};

mapping::Heightmap random_terrain(const TerrainGeneratorParams& params, std::uint64_t seed);

struct PlanningProblem {
  Pose2 start;  // body poses
  Pose2 goal;
};

// Start/goal body poses whose stances are flat and whose surroundings are free for the body,
// `min_dist_m`..`max_dist_m` apart, sampled uniformly with a seeded generator.
std::vector<PlanningProblem> random_problems(const mapping::Heightmap& map, const FootstepPlanner& planner,
                                             std::size_t count, double min_dist_m, double max_dist_m,
                                             std::uint64_t seed);

}  // namespace bipednav::planning::footstep
