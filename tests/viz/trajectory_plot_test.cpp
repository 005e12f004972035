#include "bipednav/viz/trajectory_plot.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bipednav/common/error.hpp"

namespace bipednav::viz {
namespace {

TEST(TrajectoryPlot, WritesAPngOfTheLines) {
  const auto file = std::filesystem::temp_directory_path() / "bipednav_trajectory_plot_test.png";
  std::filesystem::remove(file);
  write_trajectory_plot(file,
                        {{"ground truth", colors::kBlack, {{0, 0}, {5, 0.2}, {12, 0.7}}},
                         {"estimate", colors::kRed, {{0, 0}, {4.9, 0.1}, {11.7, 0.45}}}},
                        "test", 400.0);
  std::ifstream in(file, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  EXPECT_THROW(write_trajectory_plot(file, {{"empty", colors::kRed, {}}}, "t"), Error);
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace bipednav::viz
