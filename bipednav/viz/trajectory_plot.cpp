#include "bipednav/viz/trajectory_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bipednav/common/error.hpp"

namespace bipednav::viz {

double scale_bar_length_m(double span_m) {
  if (!(span_m > 0.0 && std::isfinite(span_m))) return 1.0;
  const double quarter = span_m / 4.0;
  const double decade = std::pow(10.0, std::floor(std::log10(quarter)));
  for (const double m : {5.0, 2.0, 1.0})
    if (m * decade <= quarter) return m * decade;
  return decade;
}

void write_trajectory_plot(const std::filesystem::path& file, const std::vector<PlotLine>& lines,
                           const std::string& title, double size_px) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = Eigen::Vector2d::Constant(-1e300);
  for (const PlotLine& l : lines)
    for (const Eigen::Vector2d& p : l.xy) {
      if (!p.allFinite()) continue;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  if (!(lo.x() <= hi.x())) throw Error("write_trajectory_plot: no finite point to draw");
  // A square-ish view with a 10 % margin, at least 1 m wide, and room for the legend on top.
  const double span = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1.0});
  const double pad = 0.1 * span;
  const int legend_px = 28 + 18 * static_cast<int>(lines.size());
  CanvasParams cp;
  cp.min_x_m = lo.x() - pad;
  cp.max_x_m = hi.x() + pad;
  cp.min_y_m = lo.y() - pad;
  cp.max_y_m = hi.y() + pad;
  cp.pixels_per_m = std::clamp(size_px / (span + 2.0 * pad), 1e-3, 2000.0);
  cp.margin_px = 40;
  cp.max_y_m += legend_px / cp.pixels_per_m;  // the legend sits above the lines
  Canvas c(cp);
  for (const PlotLine& l : lines) {
    c.polyline(l.xy, l.color, 2.0);
    if (!l.xy.empty()) c.circle(l.xy.front(), 4.0 / cp.pixels_per_m, l.color);
  }
  c.text_px(cp.margin_px, 22, title, colors::kBlack, 14.0);
  // The legend: a swatch (a short line, its pixel ends taken back to world coordinates) and the label.
  const auto world_of = [&](double px, double py) {
    return Eigen::Vector2d(cp.min_x_m + (px - cp.margin_px) / cp.pixels_per_m,
                           cp.max_y_m - (py - cp.margin_px) / cp.pixels_per_m);
  };
  const double x0 = cp.margin_px;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const double y = 44.0 + 18.0 * static_cast<double>(i);
    c.line(world_of(x0, y - 4.0), world_of(x0 + 24.0, y - 4.0), lines[i].color, 3.0);
    c.text_px(x0 + 32.0, y, lines[i].label, colors::kBlack, 12.0);
  }
  // Scale bar, bottom right.
  const double bar_m = scale_bar_length_m(cp.max_x_m - cp.min_x_m);
  const Eigen::Vector2d end{cp.max_x_m - 0.05 * span, cp.min_y_m + 0.04 * span};
  const Eigen::Vector2d start{end.x() - bar_m, end.y()};
  c.line(start, end, colors::kBlack, 3.0);
  char label[32];
  std::snprintf(label, sizeof(label), "%g m", bar_m);
  const Eigen::Vector2d at = c.to_pixel(start);
  c.text_px(at.x(), at.y() - 8.0, label, colors::kBlack, 12.0);
  c.write_png(file);
}

}  // namespace bipednav::viz
