#pragma once

#include <nlohmann/json.hpp>

// `bipednav bench mapping`: the local costmap's update with a synthetic Digit frame, the inflation of a
// 160 x 160 window, the heightmap's fusion of a terrain cloud and the global costmap's update.
namespace bipednav::bench {

struct MappingBenchOptions {
  int iterations = 100;  // updates to time
};

// Times `iterations` local and global updates as the robot walks 5 cm per update through the room (at
// least 200 inflations, at least 5 heightmap updates). Returns the medians (wall and thread CPU time)
// with their goals.
nlohmann::json run_mapping_bench(const MappingBenchOptions& options);

}  // namespace bipednav::bench
