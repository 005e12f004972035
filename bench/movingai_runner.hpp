#pragma once

#include <optional>
#include <vector>

#include "bipednav/common/outcome.hpp"
#include "bipednav/common/pose2.hpp"
#include "bipednav/io/movingai.hpp"
#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/planning/global/global_planner.hpp"

namespace bipednav::planning::global {

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
                                            const std::vector<io::MovingAiProblem>& problems, GlobalPlanner& planner);

}  // namespace bipednav::planning::global
