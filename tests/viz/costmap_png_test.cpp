#include "bipednav/viz/costmap_png.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "bipednav/common/rng.hpp"
#include "bipednav/io/map_server.hpp"

namespace fs = std::filesystem;
using namespace bipednav::mapping;

// The coloured PNG keeps lethal cells black, which map_server reads back as lethal.
TEST(CostmapPng, LethalCellsStayBlack) {
  bipednav::Rng rng(5);
  Costmap2D map({37, 21, 0.1, -1.5, 2.25}, kFree);
  for (auto& v : map.data()) v = rng.bernoulli(0.2) ? kLethal : (rng.bernoulli(0.2) ? kUnknown : kFree);
  const fs::path dir = fs::temp_directory_path() / "bipednav_costmap_png";
  fs::create_directories(dir);
  bipednav::viz::write_costmap_png(dir / "map.png", map, 2);
  const auto img = bipednav::io::read_png_gray(dir / "map.png");
  EXPECT_EQ(img.width, 74);
  EXPECT_EQ(img.height, 42);
  EXPECT_EQ(img.pixels[0] == 0, map.cost(0, 20) == kLethal);
  fs::remove_all(dir);
}
