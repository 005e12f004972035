#include "bipednav/mapping/inflation.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::mapping {

void InflationParams::validate() const {
  require(std::isfinite(inscribed_radius_m) && inscribed_radius_m >= 0.0, "inscribed_radius_m", ">= 0 m");
  require(std::isfinite(inflation_radius_m) && inflation_radius_m >= inscribed_radius_m && inflation_radius_m <= 20.0,
          "inflation_radius_m", ">= inscribed_radius_m and <= 20 m");
  require(std::isfinite(cost_scaling_factor) && cost_scaling_factor >= 0.0, "cost_scaling_factor", ">= 0 (1/m)");
}

std::uint8_t inflation_cost(double distance_m, const InflationParams& p) {
  if (distance_m <= 0.0) return kLethal;
  const double eps = 1e-9;
  if (distance_m <= p.inscribed_radius_m + eps) return kInscribed;
  if (distance_m > p.inflation_radius_m + eps) return kFree;
  const double factor = std::exp(-p.cost_scaling_factor * (distance_m - p.inscribed_radius_m));
  return static_cast<std::uint8_t>((kInscribed - 1) * factor);
}

Inflator::Inflator(const InflationParams& params, double resolution_m) : params_(params), resolution_m_(resolution_m) {
  params.validate();
  require(std::isfinite(resolution_m) && resolution_m > 0.0, "resolution_m", "> 0 m");
  radius_cells_ = static_cast<int>(std::ceil(params.inflation_radius_m / resolution_m - 1e-9));
  require(radius_cells_ <= 120, "inflation_radius_m", "at most 120 cells (inflation_radius_m / resolution_m)");
  const int cap = radius_cells_ + 1;
  const int max_d2 = cap * cap + radius_cells_ * radius_cells_;
  cost_of_d2_.resize(static_cast<std::size_t>(max_d2) + 1);
  for (int d2 = 0; d2 <= max_d2; ++d2) cost_of_d2_[d2] = inflation_cost(std::sqrt(double(d2)) * resolution_m, params);
}

void Inflator::inflate(const Costmap2D& obstacles, Costmap2D& out, CellRect region) {
  const GridGeometry& g = obstacles.geometry();
  if (out.width() != g.width || out.height() != g.height) out = Costmap2D(g, kFree);
  if (out.geometry().origin_x_m != g.origin_x_m || out.geometry().origin_y_m != g.origin_y_m) out = Costmap2D(g, kFree);
  region = region.clipped(g);
  if (region.empty()) return;
  const int R = radius_cells_, cap = R + 1;
  // Window of the column pass: the region plus R rows above/below (clipped to the grid) and R
  // padding columns left/right (outside the grid they hold "no obstacle within reach").
  const int wy0 = std::max(0, region.y0 - R), wy1 = std::min(g.height, region.y1 + R);
  const int pw = region.width() + 2 * R;  // padded width
  const int rows = wy1 - wy0;
  g2_.assign(static_cast<std::size_t>(pw) * rows, static_cast<std::int16_t>(cap));
  const int gx0 = std::max(0, region.x0 - R), gx1 = std::min(g.width, region.x1 + R);
  const int off = region.x0 - R;  // grid x of padded column 0
  const auto* src = obstacles.data().data();
  // Column pass, downwards then upwards, vectorised along rows: g = vertical distance, capped.
  for (int r = 0; r < rows; ++r) {
    std::int16_t* cur = &g2_[static_cast<std::size_t>(r) * pw];
    const std::int16_t* prev = r > 0 ? cur - pw : nullptr;
    const std::uint8_t* s = src + g.index(0, wy0 + r);
    for (int x = gx0; x < gx1; ++x) {
      const std::int16_t up = prev ? static_cast<std::int16_t>(std::min<int>(prev[x - off] + 1, cap)) : cap;
      cur[x - off] = s[x] == kLethal ? std::int16_t{0} : up;
    }
  }
  for (int r = rows - 2; r >= 0; --r) {
    std::int16_t* cur = &g2_[static_cast<std::size_t>(r) * pw];
    const std::int16_t* next = cur + pw;
    for (int i = 0; i < pw; ++i) cur[i] = std::min<std::int16_t>(cur[i], static_cast<std::int16_t>(next[i] + 1));
  }
  for (auto& v : g2_) v = static_cast<std::int16_t>(std::min<int>(v, cap) * std::min<int>(v, cap));
  // Row pass: d2(x) = min_{|dx|<=R} dx^2 + g2(x+dx); exact whenever the true distance is <= R.
  const int w = region.width();
  row_.resize(static_cast<std::size_t>(w));
  auto* dst = out.data().data();
  for (int y = region.y0; y < region.y1; ++y) {
    const std::int16_t* gr = &g2_[static_cast<std::size_t>(y - wy0) * pw];
    std::int16_t* d2 = row_.data();
    for (int i = 0; i < w; ++i) d2[i] = gr[i + R];
    for (int dx = 1; dx <= R; ++dx) {
      const std::int16_t dd = static_cast<std::int16_t>(dx * dx);
      const std::int16_t* l = gr + R - dx;
      const std::int16_t* rr = gr + R + dx;
      for (int i = 0; i < w; ++i) {
        const std::int16_t m = std::min(l[i], rr[i]);
        d2[i] = std::min(d2[i], static_cast<std::int16_t>(m + dd));
      }
    }
    std::uint8_t* o = dst + g.index(region.x0, y);
    for (int i = 0; i < w; ++i) o[i] = cost_of_d2_[static_cast<std::size_t>(d2[i])];
  }
}

}  // namespace bipednav::mapping
