#include "bench/movingai_runner.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <system_error>

#include "bipednav/common/error.hpp"
#include "bipednav/planning/global/global_planner_factory.hpp"

namespace bipednav::bench {

using planning::global::GlobalPlanner;
using planning::global::make_global_planner;
using planning::global::PlanResult;

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

nlohmann::json movingai_report(const std::vector<MovingAiRowResult>& rows, const std::string& planner) {
  using nlohmann::json;
  json out = json::array();
  double max_err = 0.0, total_ms = 0.0;
  int solved = 0;
  for (const auto& r : rows) {
    const auto& p = r.problem;
    json row = {
        {"start_cell", {p.start_x, p.start_y}},     {"goal_cell", {p.goal_x, p.goal_y}}, {"length_cells", nullptr},
        {"optimal_length_cells", p.optimal_length}, {"expansions", r.expansions},        {"time_ms", r.time_ms}};
    if (r.length) {
      row["length_cells"] = *r.length;
      max_err = std::max(max_err, std::abs(*r.length - p.optimal_length));
      ++solved;
    } else {
      row["outcome"] = outcome_name(r.result.outcome);
      max_err = std::max(max_err, std::abs(p.optimal_length));  // an unsolved row counts fully
    }
    total_ms += r.time_ms;
    out.push_back(std::move(row));
  }
  return {{"planner", planner},
          {"rows", out},
          {"summary",
           {{"rows", rows.size()}, {"solved", solved}, {"max_abs_error_cells", max_err}, {"total_time_ms", total_ms}}}};
}

std::filesystem::path find_movingai_dir(const std::string& given) {
  namespace fs = std::filesystem;
  if (!given.empty()) return given;
  std::vector<fs::path> roots = {fs::current_path()};
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) roots.push_back(exe.parent_path());
  for (fs::path p : roots)
    for (; !p.empty(); p = p.parent_path()) {
      if (fs::exists(p / "tests/data/movingai/maps")) return p / "tests/data/movingai";
      if (p == p.parent_path()) break;
    }
  return {};
}

nlohmann::json movingai_first_plans(const std::filesystem::path& dir) {
  using nlohmann::json;
  json out = json::array();
  for (const char* name : {"arena", "den312d", "lak303d", "Berlin_0_256"}) {
    const auto map = io::read_movingai_map(dir / "maps" / (std::string(name) + ".map"));
    const auto problems = io::read_movingai_scen(dir / "scen" / (std::string(name) + ".map.scen"));
    json entry = {{"map", name}, {"rows", problems.size()}};
    for (const char* planner_name : {"dstar_lite", "astar"}) {
      auto planner = make_global_planner(planner_name, {});
      const auto rows = run_movingai(map, problems, *planner);
      double sum = 0.0, mx = 0.0, err = 0.0;
      for (const auto& r : rows) {
        sum += r.time_ms;
        mx = std::max(mx, r.time_ms);
        err = std::max(err, r.length ? std::abs(*r.length - r.problem.optimal_length) : 1e9);
      }
      const std::string k = planner_name;
      entry[k + "_first_plan_mean_ms"] = sum / std::max<std::size_t>(1, rows.size());
      entry[k + "_first_plan_max_ms"] = mx;
      entry[k + "_max_abs_error"] = err;
    }
    out.push_back(entry);
  }
  return out;
}

}  // namespace bipednav::bench
