#include <gtest/gtest.h>

#include <string>

#include "bipednav/common/error.hpp"
#include "bipednav/io/movingai.hpp"
#include "test_data.hpp"

using bipednav::FileError;
using namespace bipednav::io;

namespace {

void expect_file_error(const std::string& map_text, const std::string& needle) {
  try {
    parse_movingai_map(map_text, "bad.map");
    FAIL() << "no error for: " << needle;
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

void expect_scen_error(const std::string& text, const std::string& needle) {
  try {
    parse_movingai_scen(text, "bad.scen");
    FAIL() << "no error for: " << needle;
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(MovingAiMapReader, ParsesTilesAndPassability) {
  const auto m = parse_movingai_map("type octile\r\nheight 2\r\nwidth 4\r\nmap\r\n.GS@\r\nOTW.\r\n", "x.map");
  EXPECT_EQ(m.width, 4);
  EXPECT_EQ(m.height, 2);
  EXPECT_EQ(m.tile(3, 0), '@');
  EXPECT_TRUE(m.passable(0, 0));
  EXPECT_TRUE(m.passable(1, 0));
  EXPECT_TRUE(m.passable(2, 0));
  EXPECT_FALSE(m.passable(3, 0));
  EXPECT_FALSE(m.passable(0, 1));
  EXPECT_FALSE(m.passable(1, 1));
  EXPECT_FALSE(m.passable(2, 1));  // water
  EXPECT_TRUE(m.passable(3, 1));
}

TEST(MovingAiMapReader, MalformedInputNamesFileLineAndField) {
  expect_file_error("type tile\nheight 1\nwidth 1\nmap\n.\n", "bad.map:line 1: field 'type'");
  expect_file_error("type octile\nheight x\nwidth 1\nmap\n.\n", "bad.map:line 2: field 'height': expected an integer");
  expect_file_error("type octile\nheight 1\nwide 1\nmap\n.\n", "bad.map:line 3: expected 'width N'");
  expect_file_error("type octile\nheight 1\nwidth 0\nmap\n.\n", "line 3: field 'width': expected a positive");
  expect_file_error("type octile\nheight 1\nwidth 1\nmaps\n.\n", "line 4: expected the line 'map'");
  expect_file_error("type octile\nheight 2\nwidth 2\nmap\n..\n.\n", "line 6: map row 1: expected 2 tiles, got 1");
  expect_file_error("type octile\nheight 2\nwidth 2\nmap\n..\n", "map row 1: expected 2 rows, got end of file");
  expect_file_error("type octile\nheight 1\nwidth 2\nmap\n..\n..\n", "line 6: unexpected text");
  // From fuzz/fuzz_movingai_map: a huge header must not size the tile buffer (out of memory).
  expect_file_error("type octile\nheight 2147483647\nwidth 2147483647\nmap\n..\n",
                    "map row 0: expected 2147483647 tiles");
  EXPECT_THROW(read_movingai_map("/nonexistent/x.map"), FileError);
}

TEST(MovingAiScenReader, ParsesRowsAndSkipsEmptyLines) {
  const auto rows = parse_movingai_scen(
      "version 1\n0\tmaps/dao/arena.map\t49\t49\t1\t11\t1\t12\t1\n\n3\tx.map\t49\t49\t2\t3\t40\t41\t3.41421\n",
      "x.scen");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].map, "maps/dao/arena.map");
  EXPECT_EQ(rows[1].bucket, 3);
  EXPECT_EQ(rows[1].start_x, 2);
  EXPECT_EQ(rows[1].start_y, 3);
  EXPECT_EQ(rows[1].goal_x, 40);
  EXPECT_EQ(rows[1].goal_y, 41);
  EXPECT_DOUBLE_EQ(rows[1].optimal_length, 3.41421);
}

TEST(MovingAiScenReader, MalformedInputNamesFileLineAndField) {
  expect_scen_error("version 2\n", "bad.scen:line 1: field 'version'");
  expect_scen_error("version 1\n0\tm\t4\t4\t1\t1\t2\n", "bad.scen:line 2: expected 9 TAB-separated fields, got 7");
  expect_scen_error("version 1\n0\tm\t4\t4\ta\t1\t2\t2\t1\n", "line 2: field 'start_x': expected an integer");
  expect_scen_error("version 1\n0\tm\t4\t4\t1\t1\t2\t2\tfar\n", "line 2: field 'optimal_length'");
  expect_scen_error("version 1\n0\tm\t4\t4\t1\t1\t2\t9\t1\n", "line 2: field 'goal_y': outside the map height");
}

TEST(MovingAiReaders, ReadTheSharedBenchmarkFiles) {
  BIPEDNAV_REQUIRE_DATA(map_file, "movingai/maps/Berlin_0_256.map");
  BIPEDNAV_REQUIRE_DATA(scen_file, "movingai/scen/Berlin_0_256.map.scen");
  const auto m = read_movingai_map(map_file);  // CRLF line ends
  EXPECT_EQ(m.width, 256);
  EXPECT_EQ(m.height, 256);
  const auto rows = read_movingai_scen(scen_file);
  EXPECT_EQ(rows.size(), 930u);
  EXPECT_EQ(rows[0].start_x, 248);
  EXPECT_DOUBLE_EQ(rows[0].optimal_length, 2.0);
  BIPEDNAV_REQUIRE_DATA(den_scen, "movingai/scen/den312d.map.scen");
  EXPECT_EQ(read_movingai_scen(den_scen).size(), 320u);  // ends with an empty line
}

}  // namespace
