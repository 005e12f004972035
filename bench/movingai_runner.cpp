#include "bench/movingai_runner.hpp"

#include "bipednav/common/error.hpp"

namespace bipednav::planning::global {

mapping::Costmap2D movingai_costmap(const io::MovingAiMap& map) {
  mapping::GridGeometry g;
  g.width = map.width;
  g.height = map.height;
  g.resolution_m = 1.0;
  mapping::Costmap2D costmap(g, mapping::kFree);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      if (!map.passable(x, y)) costmap.set_cost(x, y, mapping::kLethal);
  return costmap;
}

Pose2 movingai_pose(int x, int y) { return {x + 0.5, y + 0.5, 0.0}; }

std::vector<MovingAiRowResult> run_movingai(const io::MovingAiMap& map,
                                            const std::vector<io::MovingAiProblem>& problems, GlobalPlanner& planner) {
  const mapping::Costmap2D costmap = movingai_costmap(map);
  std::vector<MovingAiRowResult> out;
  out.reserve(problems.size());
  for (const auto& p : problems) {
    if (p.map_width != map.width || p.map_height != map.height)
      throw Error("Moving AI problem for a " + std::to_string(p.map_width) + " x " + std::to_string(p.map_height) +
                  " map does not fit map '" + map.name + "' (" + std::to_string(map.width) + " x " +
                  std::to_string(map.height) + ")");
    planner.reset();
    const PlanResult r =
        planner.plan(costmap, movingai_pose(p.start_x, p.start_y), movingai_pose(p.goal_x, p.goal_y), {});
    MovingAiRowResult row{p, r.result, std::nullopt, r.expansions, r.time_ms};
    if (r.result.ok()) row.length = r.cost;
    out.push_back(std::move(row));
  }
  return out;
}

}  // namespace bipednav::planning::global
