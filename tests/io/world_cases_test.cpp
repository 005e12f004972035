#include "bipednav/io/world_cases.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "bipednav/common/error.hpp"

namespace {

using namespace bipednav;

std::filesystem::path write_text(const std::string& name, const std::string& text) {
  const auto file = std::filesystem::temp_directory_path() / name;
  std::ofstream(file) << text;
  return file;
}

TEST(WorldCases, ReadsKeysDefaultsAndComments) {
  const auto file =
      write_text("bipednav_cases_ok.txt",
                 "# two cases\n"
                 "world=a/corridor.world start=0.9,0.1 goal=10,-0.5,1.5 robot=digit\n"
                 "\n"
                 "world=hall.world start=1,2,0 goal=3,4,0 tolerance=0.1,0.3 time_limit=45 seed=28 name=h  # c\n");
  const auto cases = io::read_world_cases(file);
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[0].world, "a/corridor.world");
  EXPECT_EQ(cases[0].name, "corridor_line2");
  EXPECT_EQ(cases[0].robot, "digit");
  EXPECT_EQ(cases[0].start, (Pose2{0.9, 0.1, 0.0}));
  EXPECT_EQ(cases[0].goal, (Pose2{10, -0.5, 1.5}));
  EXPECT_DOUBLE_EQ(cases[0].goal_tolerance_m, 0.2);
  EXPECT_DOUBLE_EQ(cases[0].time_limit_s, 180.0);
  EXPECT_EQ(cases[0].seed, 1u);
  EXPECT_EQ(cases[1].name, "h");
  EXPECT_TRUE(cases[1].robot.empty());
  EXPECT_DOUBLE_EQ(cases[1].goal_tolerance_m, 0.1);
  EXPECT_DOUBLE_EQ(cases[1].goal_tolerance_rad, 0.3);
  EXPECT_DOUBLE_EQ(cases[1].time_limit_s, 45.0);
  EXPECT_EQ(cases[1].seed, 28u);
}

TEST(WorldCases, WrittenCasesReadBackTheSame) {
  io::WorldCase c;
  c.name = "crowd_3";
  c.world = "crowd_3.world";
  c.start = {0.1 + 0.2, -1.0 / 3.0, 0.25};
  c.goal = {9.0, 1e-3, -0.5};
  c.goal_tolerance_m = 0.15;
  c.time_limit_s = 81;
  c.seed = 18446744073709551615u;
  const auto file = std::filesystem::temp_directory_path() / "bipednav_cases_rt.txt";
  io::write_world_cases(file, {c, c});
  const auto back = io::read_world_cases(file);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].name, c.name);
  EXPECT_EQ(back[1].world, c.world);
  EXPECT_EQ(back[1].start, c.start);
  EXPECT_EQ(back[1].goal, c.goal);
  EXPECT_EQ(back[1].goal_tolerance_m, c.goal_tolerance_m);
  EXPECT_EQ(back[1].time_limit_s, c.time_limit_s);
  EXPECT_EQ(back[1].seed, c.seed);
}

TEST(WorldCases, ErrorsNameFileLineAndKey) {
  auto message = [](const std::string& text) {
    try {
      io::read_world_cases(write_text("bipednav_cases_bad.txt", text));
    } catch (const FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("world=a.world start=0,0\n").find("line 1 (goal): missing"), std::string::npos);
  EXPECT_NE(message("\nworld=a.world start=0,x goal=1,1\n").find("line 2 (start): expected x,y"), std::string::npos);
  EXPECT_NE(message("world=a.world start=0,0 goal=1,1 speed=3\n").find("(speed): unknown key"), std::string::npos);
  EXPECT_NE(message("world=a.world start=0,0 goal=1,1 goal=2,2\n").find("(goal): given twice"), std::string::npos);
  EXPECT_NE(message("world=a.world start=0,0 goal=1,1 time_limit=-5\n").find("positive"), std::string::npos);
  EXPECT_NE(message("world=a.world start=0,0 goal=1,nan\n").find("(goal)"), std::string::npos);
  EXPECT_NE(message("world=a.world start=0,0 goal=1,1 seed=-2\n").find("(seed): expected a whole number"),
            std::string::npos);
  EXPECT_NE(message("world=a.world start=0,0 goal=1,1 seed=2.5\n").find("(seed)"), std::string::npos);
  EXPECT_NE(message("# nothing\n").find("no cases"), std::string::npos);
  EXPECT_THROW(io::read_world_cases("/nonexistent/cases.txt"), FileError);
}

}  // namespace
