#include "bipednav/viz/figure_legend.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bipednav::viz {

namespace {

void draw_mark(Canvas& c, const LegendEntry& e, const PixelRect& s) {
  const double cx = s.x + 0.5 * s.w, cy = s.y + 0.5 * s.h;
  switch (e.mark) {
    case LegendMark::kLine:
      c.line_px({s.x, cy}, {s.right(), cy}, e.color, 3.0);
      break;
    case LegendMark::kBox:
      c.rect_px({s.x + 2, s.y + 2, s.w - 4, s.h - 4}, e.fill.a > 0 ? e.fill : e.color, e.color, 1.0);
      break;
    case LegendMark::kRing:
      c.circle_px({cx, cy}, 0.32 * s.h, e.fill, e.color, 2.0);
      break;
    case LegendMark::kDot:
      c.circle_px({cx, cy}, 0.25 * s.h, e.color);
      break;
    case LegendMark::kArrow:
      c.line_px({s.x + 2, cy}, {s.right() - 3, cy}, e.color, 2.5);
      c.line_px({s.right() - 3, cy}, {s.right() - 9, cy - 5}, e.color, 2.5);
      c.line_px({s.right() - 3, cy}, {s.right() - 9, cy + 5}, e.color, 2.5);
      break;
    case LegendMark::kCross:
      c.line_px({cx - 5, cy - 5}, {cx + 5, cy + 5}, e.color, 2.5);
      c.line_px({cx - 5, cy + 5}, {cx + 5, cy - 5}, e.color, 2.5);
      break;
  }
}

}  // namespace

PixelRect legend_extent(const Canvas& canvas, const std::vector<LegendEntry>& entries, const LegendStyle& st) {
  double text_w = 0.0;
  for (const auto& e : entries) text_w = std::max(text_w, canvas.text_width_px(e.label, st.font_px));
  return {0, 0, 3 * st.pad_px + st.swatch_px + text_w, 2 * st.pad_px + st.row_px * static_cast<double>(entries.size())};
}

PixelRect draw_legend(Canvas& canvas, double x_px, double y_px, const std::vector<LegendEntry>& entries,
                      const LegendStyle& st) {
  PixelRect box = legend_extent(canvas, entries, st);
  box.x = x_px, box.y = y_px;
  canvas.rect_px(box, {1, 1, 1, 0.9}, colors::kGrey, 1.0);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const double top = y_px + st.pad_px + st.row_px * static_cast<double>(i);
    draw_mark(canvas, entries[i], {x_px + st.pad_px, top + 1, st.swatch_px, st.row_px - 2});
    canvas.text_px(x_px + 2 * st.pad_px + st.swatch_px, top + 0.5 * st.row_px + 0.35 * st.font_px, entries[i].label,
                   colors::kBlack, st.font_px);
  }
  return box;
}

double scale_bar_length_m(double max_m) {
  if (!(max_m > 0.0) || !std::isfinite(max_m)) return 0.0;
  const double decade = std::pow(10.0, std::floor(std::log10(max_m)));
  for (const double f : {5.0, 2.0, 1.0})
    if (f * decade <= max_m * (1 + 1e-12)) return f * decade;
  return decade;
}

PixelRect draw_scale_bar(Canvas& canvas, double x_px, double y_px, double max_px) {
  const double ppm = canvas.params().pixels_per_m;
  const double len_m = scale_bar_length_m(max_px / ppm);
  const double len_px = len_m * ppm;
  char label[32];
  if (len_m >= 1.0)
    std::snprintf(label, sizeof label, "%g m", len_m);
  else
    std::snprintf(label, sizeof label, "%g cm", len_m * 100.0);
  // Two halves (black, white) with the ends labelled "0" and the length.
  canvas.rect_px({x_px, y_px, len_px, 5}, colors::kBlack);
  canvas.rect_px({x_px + 0.5 * len_px, y_px, 0.5 * len_px, 5}, colors::kWhite, colors::kBlack, 1.0);
  canvas.text_px(x_px - 3, y_px + 19, "0", colors::kBlack, 12.0);
  const double w = canvas.text_width_px(label);
  canvas.text_px(x_px + len_px - 0.5 * w, y_px + 19, label, colors::kBlack, 12.0);
  return {x_px - 3, y_px, len_px + 0.5 * w + 3, 22};
}

PixelRect draw_color_ramp(Canvas& canvas, const PixelRect& area, Color lo, Color hi, const std::string& lo_label,
                          const std::string& hi_label, const std::string& caption) {
  const PixelRect box{area.x, area.y, std::min(area.w - 8, 140.0), 12};
  canvas.text_px(box.x, box.y + 12, caption, colors::kBlack, 12.0);
  const PixelRect ramp{box.x, box.y + 18, box.w, box.h};
  const int steps = 32;
  for (int i = 0; i < steps; ++i) {
    const double f = (i + 0.5) / steps;
    const Color c{lo.r + f * (hi.r - lo.r), lo.g + f * (hi.g - lo.g), lo.b + f * (hi.b - lo.b),
                  lo.a + f * (hi.a - lo.a)};
    canvas.rect_px({ramp.x + ramp.w * i / steps, ramp.y, ramp.w / steps + 0.5, ramp.h}, c);
  }
  canvas.rect_px(ramp, colors::kNone, colors::kGrey, 1.0);
  canvas.text_px(ramp.x, ramp.bottom() + 14, lo_label, colors::kBlack, 11.0);
  const double w = canvas.text_width_px(hi_label, 11.0);
  canvas.text_px(ramp.right() - w, ramp.bottom() + 14, hi_label, colors::kBlack, 11.0);
  return {box.x, box.y, box.w, ramp.bottom() + 16 - box.y};
}

namespace {
constexpr int kTitleBandPx = 26;
constexpr double kScaleBarPx = 50.0;  // the scale bar and its label under the legend
}  // namespace

CanvasParams with_legend_bands(CanvasParams params, const std::vector<LegendEntry>& entries, double extra_h_px) {
  const Canvas scratch(CanvasParams{0, 0, 1, 1, 1});  // measures the legend's text
  const PixelRect box = legend_extent(scratch, entries);
  params.top_px = kTitleBandPx;
  params.right_px = static_cast<int>(std::ceil(std::max(box.w, 120.0))) + 12;
  const double world_h = (params.max_y_m - params.min_y_m) * params.pixels_per_m;
  params.bottom_px = static_cast<int>(std::ceil(std::max(0.0, box.h + kScaleBarPx + extra_h_px - world_h)));
  return params;
}

PixelRect draw_title_and_legend(Canvas& canvas, const std::string& title, const std::vector<LegendEntry>& entries) {
  const PixelRect world = canvas.world_rect();
  canvas.text_px(world.x, world.y - 8, title, colors::kBlack, 14.0);
  const double x = world.right() + 12, w = canvas.params().right_px - 12;
  const PixelRect box = draw_legend(canvas, x, world.y, entries);
  draw_scale_bar(canvas, x + 6, box.bottom() + 16, w - 12);
  const double top = box.bottom() + kScaleBarPx;
  return {x, top, w, std::max(0.0, canvas.height_px() - top)};
}

}  // namespace bipednav::viz
