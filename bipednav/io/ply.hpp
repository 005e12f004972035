#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "bipednav/common/point_cloud.hpp"

namespace bipednav::io {

// Reads the vertices of a PLY file (format ascii 1.0 or binary_little_endian 1.0). The `vertex`
// element needs scalar properties x, y, z (any numeric type); `intensity` is mapped when present;
// other properties (normals, colours, lists) are skipped, other elements before `vertex` are
// skipped, elements after it are not read. binary_big_endian and malformed files throw FileError
// naming the file, the header line or property, and what was expected.
PointCloud read_ply(const std::filesystem::path& file);
PointCloud parse_ply(std::string_view bytes, const std::string& name);

}  // namespace bipednav::io
