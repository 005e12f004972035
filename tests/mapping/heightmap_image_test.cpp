#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "bipednav/common/error.hpp"
#include "bipednav/mapping/map_io.hpp"
#include "test_data.hpp"

using namespace bipednav;

TEST(HeightmapImage, GridMapGradientFallsLeftToRight) {
  BIPEDNAV_REQUIRE_DATA(png, "heightmaps/grid_map/linearGradient_horizontal.png");
  const mapping::Heightmap m = mapping::read_heightmap_image(png, {0.02, -0.5, 1.0, 0.0, 0.0});
  ASSERT_EQ(m.geometry().width, 300);
  ASSERT_EQ(m.geometry().height, 300);
  EXPECT_NEAR(m.height(0, 150), 1.0, 0.01);
  EXPECT_NEAR(m.height(299, 150), -0.5, 0.01);
  // The upstream analytic slope: 1.5 m over 5.98 m.
  const double slope = (m.height(50, 100) - m.height(250, 100)) / (200 * 0.02);
  EXPECT_NEAR(slope, 1.5 / 5.98, 0.01);
  EXPECT_NEAR(m.height(120, 10), m.height(120, 290), 1e-6);  // constant along y
}

TEST(HeightmapImage, YamlSidecarAndBadInput) {
  BIPEDNAV_REQUIRE_DATA(png, "heightmaps/grid_map/linearGradient_horizontal.png");
  const auto dir = std::filesystem::temp_directory_path() / "bipednav_hm_test";
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(png, dir / "g.png", std::filesystem::copy_options::overwrite_existing);
  std::ofstream(dir / "g.yaml") << "image: g.png\nresolution_m: 0.01\nmin_height_m: 0.0\nmax_height_m: 0.1\n";
  const auto m = mapping::read_heightmap_image(dir / "g.yaml");
  EXPECT_DOUBLE_EQ(m.geometry().resolution_m, 0.01);
  EXPECT_NEAR(m.height(0, 0), 0.1, 1e-3);
  std::ofstream(dir / "bad.yaml") << "image: g.png\nresolution_m: -1\n";
  EXPECT_THROW(mapping::read_heightmap_image(dir / "bad.yaml"), FileError);
  std::ofstream(dir / "typo.yaml") << "image: g.png\nresolutoin_m: 0.1\n";
  EXPECT_THROW(mapping::read_heightmap_image(dir / "typo.yaml"), FileError);
  std::ofstream(dir / "notpng.png") << "definitely not a png";
  EXPECT_THROW(mapping::read_heightmap_image(dir / "notpng.png"), FileError);
  EXPECT_THROW(mapping::read_heightmap_image(dir / "missing.png"), FileError);
  // A YAML whose image does not exist names the YAML (found by fuzz_heightmap_image).
  std::ofstream(dir / "abs.yaml") << "image: /nothere.png\nresolution_m: 0.01\n";
  try {
    mapping::read_heightmap_image(dir / "abs.yaml");
    ADD_FAILURE() << "no error for a missing image";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("abs.yaml"), std::string::npos) << e.what();
  }
  // An image name longer than the system allows is a missing image, not a filesystem_error.
  std::ofstream(dir / "long.yaml") << "image: " << std::string(5000, 'x') << ".png\nresolution_m: 0.01\n";
  EXPECT_THROW(mapping::read_heightmap_image(dir / "long.yaml"), FileError);
  std::filesystem::remove_all(dir);
}
