#include "bipednav/viz/trajectory_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bipednav/common/error.hpp"
#include "bipednav/viz/figure_legend.hpp"

namespace bipednav::viz {

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
  std::vector<LegendEntry> entries;
  for (const PlotLine& l : lines) entries.push_back({l.label, l.color, LegendMark::kLine});
  draw_legend(c, cp.margin_px, 32.0, entries);
  // Scale bar, bottom left, at most a quarter of the view wide.
  draw_scale_bar(c, cp.margin_px, c.height_px() - cp.margin_px + 8.0, 0.25 * (span + 2.0 * pad) * cp.pixels_per_m);
  c.write_png(file);
}

}  // namespace bipednav::viz
