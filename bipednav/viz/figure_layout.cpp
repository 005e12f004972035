#include "bipednav/viz/figure_layout.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::viz {

void FigureLayoutParams::validate() const {
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  require(std::isfinite(max_width_px) && max_width_px > 0 && std::isfinite(max_height_px) && max_height_px > 0,
          "max_width_px", "> 0 (and max_height_px)");
  require(std::isfinite(min_pixels_per_m) && min_pixels_per_m > 0 && max_pixels_per_m >= min_pixels_per_m &&
              std::isfinite(max_pixels_per_m),
          "min_pixels_per_m", "> 0 and <= max_pixels_per_m");
  require(non_negative(margin_px) && non_negative(header_px) && non_negative(title_px) && non_negative(gap_px) &&
              non_negative(legend_w_px) && non_negative(legend_h_px),
          "margin_px", ">= 0 (and every other band)");
}

bool overlap(const PixelRect& a, const PixelRect& b) {
  return a.x < b.right() && b.x < a.right() && a.y < b.bottom() && b.y < a.bottom();
}

FigureLayout figure_layout(double width_m, double height_m, std::size_t panels, const FigureLayoutParams& p) {
  p.validate();
  require(std::isfinite(width_m) && width_m > 0 && std::isfinite(height_m) && height_m > 0, "width_m",
          "a finite world extent > 0 (and height_m)");
  require(panels > 0, "panels", ">= 1");
  const double legend_band = p.legend_w_px > 0 ? p.gap_px + p.legend_w_px : 0.0;
  FigureLayout best;
  for (std::size_t cols = 1; cols <= panels; ++cols) {
    const std::size_t rows = (panels + cols - 1) / cols;
    const double c = static_cast<double>(cols), r = static_cast<double>(rows);
    const double avail_w = p.max_width_px - 2 * p.margin_px - legend_band - (c - 1) * p.gap_px;
    const double avail_h = p.max_height_px - 2 * p.margin_px - p.header_px - r * p.title_px - (r - 1) * p.gap_px;
    const double ppm =
        std::clamp(std::min(avail_w / (c * width_m), avail_h / (r * height_m)), p.min_pixels_per_m, p.max_pixels_per_m);
    if (ppm > best.pixels_per_m)
      best.pixels_per_m = ppm, best.columns = static_cast<int>(cols), best.rows = static_cast<int>(rows);
  }
  const double ppm = best.pixels_per_m, w = width_m * ppm, h = height_m * ppm;
  const double top = p.margin_px + p.header_px;
  for (std::size_t i = 0; i < panels; ++i) {
    const double col = static_cast<double>(i % static_cast<std::size_t>(best.columns));
    const double row = static_cast<double>(i / static_cast<std::size_t>(best.columns));
    const double x = p.margin_px + col * (w + p.gap_px), y = top + row * (p.title_px + h + p.gap_px);
    best.titles.push_back({x, y, w, p.title_px});
    best.panels.push_back({x, y + p.title_px, w, h});
  }
  const double panels_w = best.columns * w + (best.columns - 1) * p.gap_px;
  const double panels_h = best.rows * (p.title_px + h) + (best.rows - 1) * p.gap_px;
  best.legend = {p.margin_px + panels_w + (p.legend_w_px > 0 ? p.gap_px : 0.0), top, p.legend_w_px,
                 std::max(panels_h, p.legend_h_px)};
  best.header = {p.margin_px, p.margin_px, panels_w + legend_band, p.header_px};
  // Whole pixels, not rounded up past the limit by the last bit of the scale.
  best.width_px = static_cast<int>(std::ceil(best.legend.right() + p.margin_px - 1e-6));
  best.height_px = static_cast<int>(std::ceil(top + std::max(panels_h, p.legend_h_px) + p.margin_px - 1e-6));
  return best;
}

}  // namespace bipednav::viz
