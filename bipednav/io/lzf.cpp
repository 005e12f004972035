#include "bipednav/io/lzf.hpp"

#include <algorithm>
#include <cstring>

namespace bipednav::io {
namespace {

constexpr std::size_t kMaxLiteral = 32;         // control bytes 0..31
constexpr std::size_t kMaxOffset = 1u << 13;    // 13-bit back-reference offset (+1)
constexpr std::size_t kMaxMatch = 7 + 255 + 2;  // length code 7 + extra byte, plus the implied 2
constexpr int kHashBits = 14;

inline std::uint32_t hash3(const std::uint8_t* p) {
  const std::uint32_t v = (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | p[2];
  return (v * 2654435761u) >> (32 - kHashBits);
}

// Appends the pending literal run in[start, end) as chunks of at most 32 bytes.
void flush_literals(std::vector<std::uint8_t>& out, const std::uint8_t* in, std::size_t start, std::size_t end) {
  while (start < end) {
    const std::size_t len = std::min(kMaxLiteral, end - start);
    out.push_back(static_cast<std::uint8_t>(len - 1));
    out.insert(out.end(), in + start, in + start + len);
    start += len;
  }
}

void emit_match(std::vector<std::uint8_t>& out, std::size_t len, std::size_t off) {
  const std::size_t code = len - 2;  // 1..262
  const auto hi = static_cast<std::uint8_t>(off >> 8);
  if (code < 7) {
    out.push_back(static_cast<std::uint8_t>((code << 5) | hi));
  } else {
    out.push_back(static_cast<std::uint8_t>((7u << 5) | hi));
    out.push_back(static_cast<std::uint8_t>(code - 7));
  }
  out.push_back(static_cast<std::uint8_t>(off & 0xff));
}

}  // namespace

std::vector<std::uint8_t> lzf_compress(const std::uint8_t* in, std::size_t n) {
  std::vector<std::uint8_t> out;
  out.reserve(n + n / 32 + 16);
  std::vector<std::size_t> table(std::size_t{1} << kHashBits, SIZE_MAX);
  std::size_t ip = 0, lit_start = 0;
  while (ip + 2 < n) {
    const std::uint32_t h = hash3(in + ip);
    const std::size_t ref = table[h];
    table[h] = ip;
    if (ref != SIZE_MAX && ip - ref - 1 < kMaxOffset && std::memcmp(in + ref, in + ip, 3) == 0) {
      const std::size_t max_len = std::min(kMaxMatch, n - ip);
      std::size_t len = 3;
      while (len < max_len && in[ref + len] == in[ip + len]) ++len;
      flush_literals(out, in, lit_start, ip);
      emit_match(out, len, ip - ref - 1);
      // Index the positions inside the match too (cheap, improves the ratio on repetitive data).
      for (std::size_t k = ip + 1; k < ip + len && k + 2 < n; ++k) table[hash3(in + k)] = k;
      ip += len;
      lit_start = ip;
    } else {
      ++ip;
    }
  }
  flush_literals(out, in, lit_start, n);
  return out;
}

std::optional<std::vector<std::uint8_t>> lzf_decompress(const std::uint8_t* in, std::size_t n,
                                                        std::size_t expected_size) {
  std::vector<std::uint8_t> out(expected_size);
  std::size_t ip = 0, op = 0;
  while (ip < n) {
    const std::size_t ctrl = in[ip++];
    if (ctrl < kMaxLiteral) {
      const std::size_t len = ctrl + 1;
      if (ip + len > n || op + len > expected_size) return std::nullopt;
      std::memcpy(out.data() + op, in + ip, len);
      ip += len;
      op += len;
      continue;
    }
    std::size_t len = ctrl >> 5;
    if (len == 7) {
      if (ip >= n) return std::nullopt;
      len += in[ip++];
    }
    len += 2;
    if (ip >= n) return std::nullopt;
    const std::size_t back = ((ctrl & 0x1f) << 8) + in[ip++] + 1;
    if (back > op || op + len > expected_size) return std::nullopt;
    // Byte by byte: source and destination may overlap (runs).
    for (std::size_t k = 0; k < len; ++k, ++op) out[op] = out[op - back];
  }
  if (op != expected_size) return std::nullopt;
  return out;
}

}  // namespace bipednav::io
