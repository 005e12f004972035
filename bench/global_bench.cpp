#include <benchmark/benchmark.h>

#include "bench/replan_benchmark.hpp"
#include "bipednav/mapping/inflation.hpp"
#include "bipednav/planning/global/global_planner.hpp"
#include "bipednav/planning/global/global_planner_factory.hpp"

namespace {

using namespace bipednav;
using namespace bipednav::bench;

// The inflated three-room world with every obstacle known.
mapping::Costmap2D three_rooms_costmap() {
  const auto world = bench::make_three_rooms_world(0.1);
  mapping::Costmap2D out;
  mapping::Inflator(mapping::InflationParams{0.25, 0.8, 3.0}, 0.1).inflate(world.truth, out);
  return out;
}

void first_plan(benchmark::State& state, const char* planner_name) {
  const auto map = three_rooms_costmap();
  const auto world = bench::make_three_rooms_world(0.1);
  auto planner = planning::global::make_global_planner(planner_name, {});
  std::size_t expansions = 0;
  for (auto _ : state) {
    planner->reset();
    const auto r = planner->plan(map, world.start, world.goal, {});
    expansions = r.expansions;
    benchmark::DoNotOptimize(r.cost);
  }
  state.counters["expansions"] = static_cast<double>(expansions);
}

void BM_DStarLiteFirstPlanThreeRooms(benchmark::State& s) { first_plan(s, "dstar_lite"); }
void BM_AStarPlanThreeRooms(benchmark::State& s) { first_plan(s, "astar"); }
BENCHMARK(BM_DStarLiteFirstPlanThreeRooms)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AStarPlanThreeRooms)->Unit(benchmark::kMillisecond);

// One incremental repair: the robot moves one cell and a cell on its path toggles.
void BM_DStarLiteRepairThreeRooms(benchmark::State& state) {
  auto map = three_rooms_costmap();
  const auto world = bench::make_three_rooms_world(0.1);
  auto planner = planning::global::make_global_planner("dstar_lite", {});
  const auto first = planner->plan(map, world.start, world.goal, {});
  const mapping::Cell c = first.cells.at(first.cells.size() / 2);
  bool blocked = false;
  for (auto _ : state) {
    const std::uint8_t old = map.cost(c);
    map.set_cost(c, blocked ? mapping::kFree : mapping::kLethal);
    blocked = !blocked;
    const auto r = planner->plan(map, world.start, world.goal, {{c, old, map.cost(c)}});
    benchmark::DoNotOptimize(r.cost);
  }
}
BENCHMARK(BM_DStarLiteRepairThreeRooms)->Unit(benchmark::kMicrosecond);

}  // namespace
