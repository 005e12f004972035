#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace bipednav::io {

// LZF (the liblzf format that PCD's binary_compressed uses), written from the format description:
// a stream of chunks, each starting with a control byte c:
//   c < 32:  a literal run of c + 1 bytes follows;
//   c >= 32: a back reference; length L = c >> 5 (if L == 7 one more byte is added to it),
//            then one byte o; copy L + 2 bytes from (output end - ((c & 31) << 8 | o) - 1).

// Compresses `in`. Always succeeds; incompressible input grows by at most 1 byte in 32 (+1).
std::vector<std::uint8_t> lzf_compress(const std::uint8_t* in, std::size_t n);

// Decompresses `in` into exactly `expected_size` bytes. Returns nullopt when the stream is corrupt
// (a back reference before the start, a run past either end) or does not produce exactly
// `expected_size` bytes.
std::optional<std::vector<std::uint8_t>> lzf_decompress(const std::uint8_t* in, std::size_t n,
                                                        std::size_t expected_size);

}  // namespace bipednav::io
