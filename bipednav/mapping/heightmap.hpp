#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "bipednav/mapping/grid_geometry.hpp"

namespace bipednav::mapping {

// A 2.5D elevation grid: per cell a height estimate (m, world z) and its variance (m^2).
// Unobserved cells have NaN height and infinite variance. The Kalman fusion that fills it
// lives in heightmap_fusion.hpp.
class Heightmap {
 public:
  Heightmap() = default;
  explicit Heightmap(const GridGeometry& geometry)
      : geometry_(geometry),
        height_(geometry.size(), std::numeric_limits<float>::quiet_NaN()),
        variance_(geometry.size(), std::numeric_limits<float>::infinity()) {}

  const GridGeometry& geometry() const { return geometry_; }
  bool known(int x, int y) const { return std::isfinite(height_[geometry_.index(x, y)]); }
  float height(int x, int y) const { return height_[geometry_.index(x, y)]; }
  float variance(int x, int y) const { return variance_[geometry_.index(x, y)]; }
  void set(int x, int y, float h, float var) {
    height_[geometry_.index(x, y)] = h;
    variance_[geometry_.index(x, y)] = var;
  }
  void clear(int x, int y) {
    set(x, y, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity());
  }

  const std::vector<float>& heights() const { return height_; }
  std::vector<float>& heights() { return height_; }
  const std::vector<float>& variances() const { return variance_; }
  std::vector<float>& variances() { return variance_; }

 private:
  GridGeometry geometry_;
  std::vector<float> height_;
  std::vector<float> variance_;
};

}  // namespace bipednav::mapping
