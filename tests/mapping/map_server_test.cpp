#include "bipednav/io/map_server.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/mapping/map_io.hpp"
#include "test_data.hpp"

using namespace bipednav::mapping;
namespace fs = std::filesystem;

namespace {

long count(const Costmap2D& m, std::uint8_t v) { return std::count(m.data().begin(), m.data().end(), v); }

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("bipednav_map_server_" + name);
  fs::create_directories(d);
  return d;
}

void write_text(const fs::path& p, const std::string& s) { std::ofstream(p) << s; }

std::string message_of(const fs::path& yaml) {
  try {
    bipednav::mapping::read_map_server(yaml);
  } catch (const bipednav::FileError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(MapServer, TebTutorialMapsLoad) {
  BIPEDNAV_REQUIRE_DATA(corridor, "teb_tutorials/maps/corridor.yaml");
  const Costmap2D c = bipednav::mapping::read_map_server(corridor);
  EXPECT_EQ(c.width(), 500);
  EXPECT_EQ(c.height(), 120);
  EXPECT_DOUBLE_EQ(c.resolution_m(), 0.05);
  // A 3-pixel black frame around a white 25 x 6 m corridor.
  EXPECT_EQ(count(c, kLethal), 500 * 120 - 494 * 114);
  EXPECT_EQ(c.cost(2, 60), kLethal);
  EXPECT_EQ(c.cost(3, 60), kFree);
  EXPECT_EQ(c.cost(250, 117), kLethal);

  BIPEDNAV_REQUIRE_DATA(box, "teb_tutorials/maps/empty_box.yaml");
  bipednav::io::MapServerMetadata meta;
  const Costmap2D b = bipednav::mapping::read_map_server(box, &meta);
  EXPECT_EQ(b.width(), 120);
  EXPECT_EQ(b.height(), 120);
  EXPECT_DOUBLE_EQ(b.geometry().origin_x_m, -3.0);
  EXPECT_DOUBLE_EQ(b.geometry().origin_y_m, -3.0);
  EXPECT_EQ(meta.image, "empty_box.png");
  EXPECT_EQ(b.cost(*b.geometry().world_to_cell(0.0, 0.0)), kFree);
  EXPECT_EQ(b.cost(0, 60), kLethal);
  EXPECT_GT(count(b, kLethal), 4 * 2 * 116);  // a 2+ cell wall on every side

  BIPEDNAV_REQUIRE_DATA(maze, "teb_tutorials/maps/maze.yaml");
  const Costmap2D m = bipednav::mapping::read_map_server(maze);
  EXPECT_EQ(m.width(), 200);
  EXPECT_EQ(m.height(), 200);
  EXPECT_EQ(count(m, kLethal) + count(m, kFree), 200 * 200);
  EXPECT_GT(count(m, kLethal), 1000);
}

TEST(MapServer, RoundTripPgm) {
  bipednav::Rng rng(5);
  Costmap2D map({37, 21, 0.1, -1.5, 2.25}, kFree);
  for (auto& v : map.data()) v = rng.bernoulli(0.2) ? kLethal : (rng.bernoulli(0.2) ? kUnknown : kFree);
  const fs::path dir = temp_dir("roundtrip");
  bipednav::mapping::write_map_server(dir / "map.yaml", map);
  ASSERT_TRUE(fs::exists(dir / "map.pgm"));
  const Costmap2D back = bipednav::mapping::read_map_server(dir / "map.yaml");
  EXPECT_EQ(back.width(), 37);
  EXPECT_EQ(back.height(), 21);
  EXPECT_DOUBLE_EQ(back.resolution_m(), 0.1);
  EXPECT_DOUBLE_EQ(back.geometry().origin_x_m, -1.5);
  EXPECT_DOUBLE_EQ(back.geometry().origin_y_m, 2.25);
  EXPECT_TRUE(diff(map, back).empty());
}

TEST(MapServer, AsciiPgmNegateAndScale) {
  const fs::path dir = temp_dir("ascii");
  // 3 x 2 image, top row first: black, white, mid-gray / white, black, light gray.
  write_text(dir / "a.pgm", "P2\n# comment\n3 2\n255\n0 255 128\n255 0 200\n");
  write_text(dir / "a.yaml", "image: a.pgm\nresolution: 0.5\norigin: [1.0, 2.0, 0.0]\n");
  Costmap2D m = bipednav::mapping::read_map_server(dir / "a.yaml");
  EXPECT_EQ(m.cost(0, 1), kLethal);
  EXPECT_EQ(m.cost(1, 1), kFree);
  EXPECT_EQ(m.cost(2, 1), kUnknown);  // occ 0.498
  EXPECT_EQ(m.cost(2, 0), kUnknown);  // occ 0.216
  write_text(dir / "n.yaml", "image: a.pgm\nresolution: 0.5\norigin: [1.0, 2.0, 0.0]\nnegate: 1\n");
  m = bipednav::mapping::read_map_server(dir / "n.yaml");
  EXPECT_EQ(m.cost(0, 1), kFree);
  EXPECT_EQ(m.cost(1, 1), kLethal);
  write_text(dir / "s.yaml", "image: a.pgm\nresolution: 0.5\norigin: [1.0, 2.0, 0.0]\nmode: scale\n");
  m = bipednav::mapping::read_map_server(dir / "s.yaml");
  // occupancy = int(99 (0.498 - 0.196) / (0.65 - 0.196)) = 65 -> cost int(0.65 * 254) = 165
  EXPECT_EQ(m.cost(2, 1), 165);
}

TEST(MapServer, MalformedFilesNameFileAndField) {
  const fs::path dir = temp_dir("bad");
  write_text(dir / "a.pgm", "P2\n2 1\n255\n0 255\n");
  const auto bad = [&](const std::string& name, const std::string& yaml) {
    write_text(dir / name, yaml);
    return message_of(dir / name);
  };
  EXPECT_NE(message_of(dir / "missing.yaml").find("missing.yaml"), std::string::npos);
  auto msg = bad("r.yaml", "image: a.pgm\norigin: [0, 0, 0]\n");
  EXPECT_NE(msg.find("r.yaml"), std::string::npos);
  EXPECT_NE(msg.find("resolution"), std::string::npos);
  msg = bad("o.yaml", "image: a.pgm\nresolution: 0.1\norigin: [0, 0]\n");
  EXPECT_NE(msg.find("origin"), std::string::npos);
  msg = bad("y.yaml", "image: a.pgm\nresolution: 0.1\norigin: [0, 0, 0.5]\n");
  EXPECT_NE(msg.find("origin[2]"), std::string::npos);
  msg = bad("m.yaml", "image: a.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nmode: raw\n");
  EXPECT_NE(msg.find("mode"), std::string::npos);
  msg = bad("t.yaml", "image: a.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nfree_thresh: 0.9\n");
  EXPECT_NE(msg.find("free_thresh"), std::string::npos);
  msg = bad("i.yaml", "image: nothere.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_NE(msg.find("nothere.pgm"), std::string::npos);
  EXPECT_NE(msg.find("i.yaml"), std::string::npos);
  // An absolute image path that does not exist still names the YAML (found by fuzz_map_server).
  msg = bad("abs.yaml", "image: /nothere.png\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_NE(msg.find("abs.yaml"), std::string::npos);
  EXPECT_NE(msg.find("/nothere.png"), std::string::npos);
  write_text(dir / "trunc.pgm", "P5\n4 4\n255\nab");
  msg = bad("tr.yaml", "image: trunc.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_NE(msg.find("trunc.pgm"), std::string::npos);
  EXPECT_NE(msg.find("pixels"), std::string::npos);
  write_text(dir / "junk.png", "not a png");
  msg = bad("p.yaml", "image: junk.png\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_NE(msg.find("junk.png"), std::string::npos);
  msg = bad("s.yaml", "image: [a\n");
  EXPECT_NE(msg.find("s.yaml"), std::string::npos);
}

// From fuzz/fuzz_map_server: a header of 20000 x 20000 pixels in a 30-byte file must not
// allocate the pixel buffers (800 MB) before finding the data missing.
TEST(MapServer, PgmSizeIsCheckedAgainstTheFileBeforeAllocating) {
  const fs::path dir = temp_dir("huge");
  const auto error = [&](const std::string& pgm) {
    write_text(dir / "h.pgm", pgm);
    try {
      bipednav::io::read_pgm(dir / "h.pgm");
    } catch (const bipednav::FileError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error("P5\n20000 20000\n255\n").find("h.pgm:pixels: expected 400000000 bytes of pixel data, got 0"),
            std::string::npos);
  EXPECT_NE(error("P2\n20000 20000\n255\n0 1\n").find("h.pgm:pixels: expected 800000000 bytes of pixel data, got 4"),
            std::string::npos);
  EXPECT_NE(error("P5\n2 1\n65535\n\x01\x02\x03").find("expected 4 bytes of pixel data, got 3"), std::string::npos);
  write_text(dir / "ok.pgm", "P2\n3 1\n255\n0 255 0");  // 2 n - 1 characters is enough
  EXPECT_EQ(bipednav::io::read_pgm(dir / "ok.pgm").pixels, (std::vector<std::uint8_t>{0, 255, 0}));
}
