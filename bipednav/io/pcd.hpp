#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "bipednav/common/point_cloud.hpp"

namespace bipednav::io {

enum class PcdEncoding { ascii, binary, binary_compressed };

// Reads a PCD file (v0.5-0.7 headers; DATA ascii, binary or binary_compressed = LZF over a
// field-major layout). Any field layout is accepted: x, y, z are required (COUNT 1, any numeric
// TYPE); these optional fields are mapped when present with COUNT 1:
//   intensity      -> intensities (any numeric type)
//   time or t      -> time_offsets_s: TYPE F is taken as seconds, TYPE U/I as nanoseconds
//                     (Velodyne drivers write float seconds, Ouster drivers uint32 ns)
//   ring           -> rings (integer in [0, 65535])
// Everything else (rgb, rgba, normals, COUNT > 1 fields) is skipped. VIEWPOINT is checked
// (7 numbers) but not applied to the points. NaN points are kept (filters drop them); organized
// clouds are read row by row. Malformed input throws FileError naming the file, the header line
// or field and what was expected.
PointCloud read_pcd(const std::filesystem::path& file);

// Same from bytes already in memory; `name` is used in error messages.
PointCloud parse_pcd(std::string_view bytes, const std::string& name);

// Writes x y z plus intensity, time (F 4, seconds) and ring (U 2) when the cloud carries them,
// as an unorganized cloud (HEIGHT 1). ASCII uses the shortest round-trip decimal form, so all three
// encodings round-trip exactly. Throws FileError when the file cannot be written and Error when
// the cloud's optional fields do not match its point count.
void write_pcd(const std::filesystem::path& file, const PointCloud& cloud,
               PcdEncoding encoding = PcdEncoding::binary_compressed);
std::string pcd_bytes(const PointCloud& cloud, PcdEncoding encoding);

// "ascii" / "binary" / "binary_compressed" -> PcdEncoding; throws Error otherwise.
PcdEncoding pcd_encoding_from_string(const std::string& s);

namespace detail {
// A numeric value stored little-endian: kind 'F' (float, size 4/8), 'U' or 'I' (size 1/2/4/8).
double load_scalar(const std::uint8_t* p, char kind, std::size_t size);
bool valid_scalar(char kind, std::size_t size);
// Reads the whole file; throws FileError when it cannot be opened.
std::string read_file_bytes(const std::filesystem::path& file);
}  // namespace detail

}  // namespace bipednav::io
