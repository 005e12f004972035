#include "bipednav/io/ply.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>

#include "bipednav/common/error.hpp"

namespace bipednav::io {
namespace {

std::string expect_ply_error(const std::string& bytes) {
  try {
    parse_ply(bytes, "bad.ply");
  } catch (const FileError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no FileError for:\n" << bytes;
  return "";
}

TEST(Ply, ReadsAsciiWithIntensityAndFaces) {
  const std::string s =
      "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty uchar red\nproperty float intensity\nelement face 1\n"
      "property list uchar int vertex_indices\nend_header\n"
      "0 0 0 255 1.5\n1 0 -2.5 0 2\n0 1 nan 7 3\n3 0 1 2\n";
  const PointCloud c = parse_ply(s, "a.ply");
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c.points[1], Eigen::Vector3f(1.0f, 0.0f, -2.5f));
  EXPECT_TRUE(std::isnan(c.points[2].z()));
  EXPECT_EQ(c.intensities, (std::vector<float>{1.5f, 2.0f, 3.0f}));
}

TEST(Ply, ReadsBinaryLittleEndianAfterAnotherElement) {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement camera 1\nproperty list uchar float params\n"
      "element vertex 2\nproperty double x\nproperty float y\nproperty int16 z\nend_header\n";
  const auto put = [&](const auto v) { s.append(reinterpret_cast<const char*>(&v), sizeof(v)); };
  put(std::uint8_t{2});
  put(1.0f);
  put(2.0f);
  put(0.25);
  put(-1.0f);
  put(std::int16_t{3});
  put(-7.0);
  put(8.5f);
  put(std::int16_t{-2});
  const PointCloud c = parse_ply(s, "b.ply");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c.points[0], Eigen::Vector3f(0.25f, -1.0f, 3.0f));
  EXPECT_EQ(c.points[1], Eigen::Vector3f(-7.0f, 8.5f, -2.0f));
  EXPECT_FALSE(c.has_intensity());
  EXPECT_NE(expect_ply_error(s.substr(0, s.size() - 1)).find("bad.ply:element vertex 1, property 'z': truncated"),
            std::string::npos);
}

// Found by fuzz/fuzz_ply: a float list length of 1e30 was cast to an integer (undefined), and a
// binary element without properties and a huge count spun for ever.
TEST(Ply, BadListLengthsAndEmptyItemsDoNotCrashOrHang) {
  const std::string vertex = "element vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  std::string s = "ply\nformat binary_little_endian 1.0\nelement cam 1\nproperty list float uchar p\n" + vertex;
  const auto put = [&](const auto v) { s.append(reinterpret_cast<const char*>(&v), sizeof(v)); };
  put(1e30f);
  s += std::string(12, '\0');
  EXPECT_NE(expect_ply_error(s).find("bad.ply:element cam 0, property 'p': expected a non-negative whole list length"),
            std::string::npos);
  const std::string head = s.substr(0, s.find("end_header\n") + 11);
  for (const float n : {std::numeric_limits<float>::infinity(), 2.5f, 1000.0f}) {
    s = head;
    put(n);
    s += std::string(12, '\0');
    EXPECT_NE(expect_ply_error(s).find("list length"), std::string::npos) << n;
  }
  s = "ply\nformat binary_little_endian 1.0\nelement cam 18446744073709551615\n" + vertex;
  put(1.0f);
  put(2.0f);
  put(3.0f);
  const PointCloud c = parse_ply(s, "empty_items.ply");
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c.points[0], Eigen::Vector3f(1.0f, 2.0f, 3.0f));
}

TEST(Ply, MalformedFilesNameFileAndField) {
  const std::string head = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n";
  EXPECT_NE(expect_ply_error(head + "end_header\n1 2\n3 4\n").find("no property 'z'"), std::string::npos);
  const std::string xyz = head + "property float z\nend_header\n";
  EXPECT_NE(expect_ply_error(xyz + "1 2 3\n").find("truncated: expected 2 items"), std::string::npos);
  EXPECT_NE(expect_ply_error(xyz + "1 2 3\n4 x 6\n").find("bad.ply:line 9, property 'y'"), std::string::npos);
  EXPECT_NE(expect_ply_error(xyz + "1 2 3\n4 5\n").find("expected 3 vertex values"), std::string::npos);
  EXPECT_NE(expect_ply_error("plx\n").find("bad.ply:line 1: expected the magic word"), std::string::npos);
  EXPECT_NE(expect_ply_error("ply\nformat binary_big_endian 1.0\n").find("not supported"), std::string::npos);
  EXPECT_NE(
      expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\n").find("line 4: unknown property"),
      std::string::npos);
  EXPECT_NE(expect_ply_error("ply\nformat ascii 1.0\nelement vertex 1\n").find("no end_header"), std::string::npos);
  EXPECT_NE(expect_ply_error("ply\nformat ascii 1.0\nelement face 0\nend_header\n").find("no 'vertex' element"),
            std::string::npos);
  EXPECT_THROW(read_ply("/nonexistent/cloud.ply"), FileError);
}

}  // namespace
}  // namespace bipednav::io
