#include "bipednav/io/pcd.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "bipednav/common/error.hpp"
#include "bipednav/io/lzf.hpp"
#include "test_data.hpp"

namespace bipednav::io {
namespace {

std::filesystem::path tmp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("bipednav_pcd_test_" + std::to_string(::getpid()) + "_" + name);
}

PointCloud sample_cloud() {
  PointCloud c;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  c.points = {{1.0f, 2.0f, 3.0f}, {-0.1f, 1e-7f, 12345.678f}, {nan, nan, nan}, {0.3f, 0.2f, 0.1f}};
  c.intensities = {0.5f, 100.0f, 0.0f, 7.25f};
  c.time_offsets_s = {0.0f, 0.01f, 0.02f, 0.09999f};
  c.rings = {0, 15, 3, 65535};
  return c;
}

void expect_same_bits(float a, float b) {
  if (std::isnan(a)) {
    EXPECT_TRUE(std::isnan(b));
  } else {
    EXPECT_EQ(a, b);
  }
}

std::string expect_error(const std::string& bytes) {
  try {
    parse_pcd(bytes, "bad.pcd");
  } catch (const FileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no FileError for:\n" << bytes;
  return "";
}

const char* kHeader =
    "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\n"
    "VIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\n";

TEST(Lzf, RoundTripAndCorruption) {
  std::vector<std::uint8_t> data;
  for (int i = 0; i < 100000; ++i) data.push_back(static_cast<std::uint8_t>((i % 97) ^ (i / 1000)));
  for (int i = 0; i < 300; ++i) data.push_back(static_cast<std::uint8_t>(i * 7919 % 251));
  const auto packed = lzf_compress(data.data(), data.size());
  EXPECT_LT(packed.size(), data.size() / 4);
  const auto back = lzf_decompress(packed.data(), packed.size(), data.size());
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, data);
  EXPECT_FALSE(lzf_decompress(packed.data(), packed.size(), data.size() + 1));
  EXPECT_FALSE(lzf_decompress(packed.data(), packed.size() - 3, data.size()));
  const std::uint8_t bad_ref[] = {0x00, 0x41, 0x20, 0x05};  // back reference before the start
  EXPECT_FALSE(lzf_decompress(bad_ref, sizeof(bad_ref), 4));
  const std::uint8_t one[] = {7};
  const auto tiny = lzf_compress(one, 1);
  EXPECT_EQ(*lzf_decompress(tiny.data(), tiny.size(), 1), std::vector<std::uint8_t>{7});
  EXPECT_TRUE(lzf_compress(nullptr, 0).empty());
}

TEST(Pcd, RoundTripAllEncodings) {
  const PointCloud c = sample_cloud();
  for (auto enc : {PcdEncoding::ascii, PcdEncoding::binary, PcdEncoding::binary_compressed}) {
    const auto path = tmp_file("rt.pcd");
    write_pcd(path, c, enc);
    const PointCloud r = read_pcd(path);
    std::filesystem::remove(path);
    ASSERT_EQ(r.size(), c.size());
    ASSERT_EQ(r.intensities.size(), c.size());
    ASSERT_EQ(r.time_offsets_s.size(), c.size());
    ASSERT_EQ(r.rings, c.rings);
    for (std::size_t i = 0; i < c.size(); ++i) {
      for (int a = 0; a < 3; ++a) expect_same_bits(c.points[i][a], r.points[i][a]);
      EXPECT_EQ(c.intensities[i], r.intensities[i]);
      EXPECT_EQ(c.time_offsets_s[i], r.time_offsets_s[i]);
    }
  }
}

TEST(Pcd, EmptyCloudRoundTrips) {
  for (auto enc : {PcdEncoding::ascii, PcdEncoding::binary, PcdEncoding::binary_compressed})
    EXPECT_TRUE(parse_pcd(pcd_bytes(PointCloud{}, enc), "empty.pcd").empty());
}

TEST(Pcd, ReadsAnyFieldLayout) {
  const std::string bytes =
      "VERSION .7\nFIELDS rgb x normal y z t ring intensity\nSIZE 4 8 4 4 4 4 2 1\nTYPE U F F F F U U U\n"
      "COUNT 1 1 3 1 1 1 1 1\nWIDTH 1\nHEIGHT 2\nPOINTS 2\nDATA ascii\n"
      "4.2e6 1.5 0 0 1 2.5 -3 500000000 7 200\n"
      "\n0 nan 0 0 1 nan nan 0 0 0\n";
  const PointCloud c = parse_pcd(bytes, "layout.pcd");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c.points[0], Eigen::Vector3f(1.5f, 2.5f, -3.0f));
  EXPECT_FLOAT_EQ(c.time_offsets_s[0], 0.5f);  // uint t = nanoseconds
  EXPECT_EQ(c.rings[0], 7);
  EXPECT_EQ(c.intensities[0], 200.0f);
  EXPECT_TRUE(std::isnan(c.points[1].x()));
}

TEST(Pcd, ReadsPclBinaryCompressedTableScene) {
  BIPEDNAV_REQUIRE_DATA(path, "pcl/table_scene_mug_stereo_textured.pcd");
  const PointCloud c = read_pcd(path);
  ASSERT_EQ(c.size(), 307200u);
  std::size_t finite = 0, band = 0;
  for (const auto& p : c.points) {
    if (!p.allFinite()) continue;
    ++finite;
    if (p.z() >= 0.0f && p.z() <= 1.5f) ++band;
  }
  EXPECT_EQ(finite, 209280u);
  EXPECT_EQ(band, 139897u);
}

TEST(Pcd, ReadsPclAsciiPlaneTest) {
  BIPEDNAV_REQUIRE_DATA(path, "pcl/sac_plane_test.pcd");
  const PointCloud c = read_pcd(path);
  EXPECT_EQ(c.size(), 3283u);
  EXPECT_FALSE(c.has_intensity());
}

TEST(Pcd, MalformedFilesNameFileAndField) {
  const std::string h = kHeader;
  EXPECT_NE(expect_error(h + "DATA ascii\n1 2 3\n").find("truncated"), std::string::npos);
  EXPECT_NE(expect_error(h + "DATA ascii\n1 2 3\n4 5\n").find("bad.pcd:line 13: expected 3 values"), std::string::npos);
  EXPECT_NE(expect_error(h + "DATA ascii\n1 2 3\n4 five 6\n").find("field 'y'"), std::string::npos);
  EXPECT_NE(expect_error(h + "DATA binary\n" + std::string(23, '\0')).find("expected 24 bytes"), std::string::npos);
  EXPECT_NE(expect_error(h + "DATA zipped\n").find("line 11: DATA: expected ascii"), std::string::npos);
  EXPECT_NE(expect_error(h).find("no DATA line"), std::string::npos);
  std::string bad_lzf = h + "DATA binary_compressed\n";
  const std::uint32_t sizes[2] = {4, 24};
  bad_lzf.append(reinterpret_cast<const char*>(sizes), 8);
  bad_lzf += std::string("\x00\x41\xe0\x05", 4);
  EXPECT_NE(expect_error(bad_lzf).find("corrupt LZF"), std::string::npos);
  EXPECT_NE(expect_error("FIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 1\nDATA ascii\n1 2\n").find("no field 'z'"),
            std::string::npos);
  EXPECT_NE(expect_error("FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nDATA ascii\n").find("SIZE has 2 entries"),
            std::string::npos);
  EXPECT_NE(expect_error("FIELDS x y z\nSIZE 4 4 3\nTYPE F F F\nWIDTH 1\nDATA ascii\n").find("field 'z'"),
            std::string::npos);
  EXPECT_NE(
      expect_error("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nPOINTS 3\nDATA ascii\n").find("WIDTH x HEIGHT"),
      std::string::npos);
  EXPECT_THROW(read_pcd("/nonexistent/file.pcd"), FileError);
}

// From fuzz/fuzz_pcd: header sizes alone must not size the cloud (out of memory, or
// std::length_error), and WIDTH x HEIGHT or POINTS x point size must not wrap around.
TEST(Pcd, HeaderSizesBeyondTheDataAreRejectedBeforeAllocating) {
  const std::string xyz = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
  EXPECT_NE(expect_error(xyz + "WIDTH 100000000000\nDATA binary\n").find("bad.pcd:DATA: truncated: expected"),
            std::string::npos);
  EXPECT_NE(expect_error(xyz + "WIDTH 100000000000\nDATA ascii\n1 2 3\n").find("bad.pcd:DATA: truncated"),
            std::string::npos);
  EXPECT_NE(expect_error(xyz + "WIDTH 2305843009213693952\nDATA binary\n").find("POINTS x point size overflows"),
            std::string::npos);
  EXPECT_NE(expect_error(xyz + "WIDTH 4294967296\nHEIGHT 4294967296\nDATA ascii\n").find("WIDTH x HEIGHT overflows"),
            std::string::npos);
  EXPECT_NE(expect_error("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 4611686018427387904\nWIDTH 1\nDATA ascii\n")
                .find("field 'z' SIZE x COUNT overflows"),
            std::string::npos);
  std::string lzf = xyz + "WIDTH 300000000\nDATA binary_compressed\n";
  const std::uint32_t sizes[2] = {4, 3600000000u};
  lzf.append(reinterpret_cast<const char*>(sizes), 8);
  lzf += std::string("\x00\x41\xe0\x05", 4);
  EXPECT_NE(expect_error(lzf).find("4 compressed bytes cannot hold 3600000000 bytes"), std::string::npos);
}

}  // namespace
}  // namespace bipednav::io
