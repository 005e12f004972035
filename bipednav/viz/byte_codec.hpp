#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace bipednav::viz {

// Compact byte payloads for text formats (the HTML replay): zlib-wrapped deflate (RFC 1950, what
// a browser's DecompressionStream('deflate') reads) and standard base64 (RFC 4648, with padding).
std::vector<std::uint8_t> deflate_bytes(std::span<const std::uint8_t> data, int level = 9);
std::vector<std::uint8_t> inflate_bytes(std::span<const std::uint8_t> data);  // throws Error when corrupt
std::string base64_encode(std::span<const std::uint8_t> data);
std::vector<std::uint8_t> base64_decode(std::string_view text);  // throws Error on a bad character or length

// base64(deflate(data)); empty data gives an empty string.
std::string pack_bytes(std::span<const std::uint8_t> data);
std::vector<std::uint8_t> unpack_bytes(std::string_view packed);

}  // namespace bipednav::viz
