#pragma once

#include <nlohmann/json.hpp>

// `bipednav bench perception`: the voxel grid and RANSAC on PCL's test clouds and on Digit's simulated
// depth clouds, the voxel grid's reduction of those clouds, and the whole Digit frame pipeline.
namespace bipednav::bench {

struct PerceptionBenchOptions {
  int reps = 15;  // repetitions per figure (median reported)
};

// Times are thread CPU time (the machine may be shared; the goals are "on one core"), median of
// `reps` runs, with wall-clock medians beside them. The clouds (tests/data/pcl), the scenario and
// Digit's profile are looked for above the working directory and the executable; without them the
// PCL rows are skipped and the frame is synthetic. Returns the figures with their goals.
nlohmann::json run_perception_bench(const PerceptionBenchOptions& options);

}  // namespace bipednav::bench
