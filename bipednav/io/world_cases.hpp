#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "bipednav/common/pose2.hpp"

namespace bipednav::io {

// One navigation case on a Gazebo world: where the robot starts, where it must get to, how
// precisely and how soon (`bipednav bench worlds --cases FILE`).
struct WorldCase {
  std::string name;             // default: the world file's stem and the line number
  std::filesystem::path world;  // absolute, or relative to the cases file
  std::string robot;            // a profile name or file; empty: every robot of the bench
  Pose2 start, goal;
  double goal_tolerance_m = 0.2, goal_tolerance_rad = 0.2;
  double time_limit_s = 180.0;
  std::uint64_t seed = 1;  // the run's seed (sensor noise, the walker's sway): the scenario default
};

// A cases file: one case per line as space-separated key=value fields, `#` to the end of a line
// is a comment, blank lines are skipped:
//   world=worlds/corridor.world start=0.9,0.1,0 goal=10.2,-0.1,0 [robot=digit]
//   [tolerance=0.2,0.2] [time_limit=90] [seed=7] [name=corridor_1]
// Poses are x,y or x,y,yaw (metres, radians). A missing or unknown key, a malformed value or a
// non-positive tolerance or time limit, or a seed that is not a whole number >= 0, raise FileError
// naming the file, the line and the key. World paths come back as written (resolve them against the
// file's directory).
std::vector<WorldCase> read_world_cases(const std::filesystem::path& file);
// Writes cases in that format (paths as given; the reader reads them back to the same values).
void write_world_cases(const std::filesystem::path& file, const std::vector<WorldCase>& cases);

}  // namespace bipednav::io
