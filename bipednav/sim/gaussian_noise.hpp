#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "bipednav/common/rng.hpp"

namespace bipednav::sim {

// Fast standard-normal samples for per-point sensor noise (millions per simulated second):
// a table of 2^12 samples drawn once from the seeded bipednav::Rng, indexed by a splitmix64
// stream seeded from the same Rng; each 64-bit splitmix output indexes four samples (12 bits
// of each 16-bit quarter). About 1 ns per sample instead of ~20 ns; the table's empirical
// distribution is Gaussian to within sampling error (tails beyond ~3.5 sigma are absent).
// Deterministic for a given seed: operator() and fill() draw from the same stream, sample k
// being quarter k % 4 of splitmix output k / 4.
class GaussianNoise {
 public:
  explicit GaussianNoise(std::uint64_t seed) : table_(kSize) {
    Rng rng(seed);
    for (float& v : table_) v = static_cast<float>(rng.normal());
    state_ = static_cast<std::uint64_t>(rng.engine()());
  }

  // A standard normal sample (mean 0, sigma 1).
  float operator()() {
    if (quarter_ == 0) bits_ = next();
    const float v = table_[(bits_ >> (16 * quarter_)) & (kSize - 1)];
    quarter_ = (quarter_ + 1) & 3;
    return v;
  }

  // Skips n samples in O(1): the next sample is the one n calls of operator() would have reached.
  void skip(std::uint64_t n) {
    for (; n > 0 && quarter_ != 0; --n) (*this)();
    state_ += (n / 4) * kGamma;  // splitmix64's state is a counter: n / 4 outputs skipped
    for (n %= 4; n > 0; --n) (*this)();
  }

  // out.size() samples, the same as that many calls of operator().
  void fill(std::span<float> out) {
    std::size_t i = 0;
    while (i < out.size() && quarter_ != 0) out[i++] = (*this)();
    const float* t = table_.data();
    for (; i + 4 <= out.size(); i += 4) {
      const std::uint64_t b = next();
      out[i] = t[b & (kSize - 1)];
      out[i + 1] = t[(b >> 16) & (kSize - 1)];
      out[i + 2] = t[(b >> 32) & (kSize - 1)];
      out[i + 3] = t[(b >> 48) & (kSize - 1)];
    }
    while (i < out.size()) out[i++] = (*this)();
  }

 private:
  static constexpr std::uint64_t kSize = std::uint64_t{1} << 12;  // 16 KiB: stays in L1

  static constexpr std::uint64_t kGamma = 0x9E3779B97F4A7C15ull;

  std::uint64_t next() {  // splitmix64
    std::uint64_t z = (state_ += kGamma);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  std::vector<float> table_;
  std::uint64_t state_ = 0;
  std::uint64_t bits_ = 0;  // current splitmix output
  unsigned quarter_ = 0;    // next quarter of bits_ to use (0: draw a new output)
};

}  // namespace bipednav::sim
