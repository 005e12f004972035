#include <gtest/gtest.h>

#include <cmath>

#include "bench/movingai_runner.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/io/movingai.hpp"
#include "bipednav/planning/global/global_planner_factory.hpp"
#include "test_data.hpp"

using namespace bipednav;

namespace {

// Every row of a Moving AI scenario: the planner's path cost equals the published optimal
// length (octile, no corner cutting) within 1e-3.
void check_all_rows(const std::filesystem::path& map_file, const std::filesystem::path& scen_file,
                    const std::string& planner_name) {
  const auto map = io::read_movingai_map(map_file);
  const auto problems = io::read_movingai_scen(scen_file);
  ASSERT_FALSE(problems.empty());
  auto planner = planning::global::make_global_planner(planner_name, {});
  const auto rows = bench::run_movingai(map, problems, *planner);
  ASSERT_EQ(rows.size(), problems.size());
  int bad = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    const bool ok = r.length && std::abs(*r.length - r.problem.optimal_length) <= 1e-3;
    if (!ok && ++bad <= 5)
      ADD_FAILURE() << planner_name << " " << scen_file.filename() << " row " << i << ": " << r.result.message
                    << " length " << (r.length ? *r.length : -1.0) << " optimal " << r.problem.optimal_length;
  }
  EXPECT_EQ(bad, 0) << planner_name << " " << scen_file.filename();
}

class MovingAiAllRows : public ::testing::TestWithParam<std::tuple<std::string, std::string>> {};

TEST_P(MovingAiAllRows, PathCostEqualsOptimalLength) {
  const auto& [map_name, planner] = GetParam();
  BIPEDNAV_REQUIRE_DATA(map_file, "movingai/maps/" + map_name + ".map");
  BIPEDNAV_REQUIRE_DATA(scen_file, "movingai/scen/" + map_name + ".map.scen");
  check_all_rows(map_file, scen_file, planner);
}

INSTANTIATE_TEST_SUITE_P(AllMaps, MovingAiAllRows,
                         ::testing::Combine(::testing::Values("arena", "den312d", "lak303d", "Berlin_0_256"),
                                            ::testing::Values("dstar_lite", "astar")),
                         [](const auto& info) { return std::get<0>(info.param) + "_" + std::get<1>(info.param); });

TEST(MovingAiCostmap, BlockedTilesAreLethalAndRowsAreNotFlipped) {
  const auto map = io::parse_movingai_map("type octile\nheight 2\nwidth 3\nmap\n.@T\nGSW\n", "t.map");
  const auto c = bench::movingai_costmap(map);
  EXPECT_EQ(c.width(), 3);
  EXPECT_EQ(c.height(), 2);
  EXPECT_EQ(c.cost(0, 0), mapping::kFree);
  EXPECT_EQ(c.cost(1, 0), mapping::kLethal);
  EXPECT_EQ(c.cost(2, 0), mapping::kLethal);
  EXPECT_EQ(c.cost(0, 1), mapping::kFree);
  EXPECT_EQ(c.cost(1, 1), mapping::kFree);
  EXPECT_EQ(c.cost(2, 1), mapping::kLethal);
}

TEST(MovingAiRunner, RejectsProblemsForAnotherMapSize) {
  const auto map = io::parse_movingai_map("type octile\nheight 2\nwidth 3\nmap\n...\n...\n", "t.map");
  const auto probs = io::parse_movingai_scen("version 1\n0\tt.map\t4\t2\t0\t0\t1\t1\t1.41421356\n", "t.scen");
  auto planner = planning::global::make_global_planner("astar", {});
  EXPECT_THROW(bench::run_movingai(map, probs, *planner), Error);
}

}  // namespace
