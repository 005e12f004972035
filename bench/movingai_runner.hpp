#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/outcome.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/io/movingai.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/planning/global/global_planner.hpp"

namespace bipednav::bench {

// A Moving AI map as a costmap with unit cell costs: resolution 1 m, origin (0, 0), cell (x, y)
// = tile (x, y) (rows are not flipped), passable tiles kFree, all others kLethal.
mapping::Costmap2D movingai_costmap(const io::MovingAiMap& map);

// The centre of a tile as a world pose on that costmap.
Pose2 movingai_pose(int x, int y);

struct MovingAiRowResult {
  io::MovingAiProblem problem;
  Result result;
  std::optional<double> length;  // path cost (= length in cells) when a path was found
  std::size_t expansions = 0;
  double time_ms = 0.0;
};

// Plans every problem from scratch (the planner is reset before each one). Raises Error when
// a problem's map size differs from the map's.
std::vector<MovingAiRowResult> run_movingai(const io::MovingAiMap& map,
                                            const std::vector<io::MovingAiProblem>& problems,
                                            planning::global::GlobalPlanner& planner);

// `plan movingai`'s figures: {planner, rows (cells, length against the optimal, expansions, time),
// summary {rows, solved, max_abs_error_cells (an unsolved row counts its optimal length),
// total_time_ms}}.
nlohmann::json movingai_report(const std::vector<MovingAiRowResult>& rows, const std::string& planner);

// `given`, or tests/data/movingai next to the sources: searched upwards from the working directory and
// from the executable (the build directory lives inside the source tree); empty when not found.
std::filesystem::path find_movingai_dir(const std::string& given);

// `bench global`'s Moving AI rows: D* Lite and A* on every problem of arena, den312d, lak303d and
// Berlin_0_256 in `dir` (maps/, scen/): mean and largest first-plan time and the largest error
// against the optimal length (1e9 for an unsolved row), per map.
nlohmann::json movingai_first_plans(const std::filesystem::path& dir);

}  // namespace bipednav::bench
