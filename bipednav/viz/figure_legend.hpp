#pragma once

#include <string>
#include <vector>

#include "bipednav/viz/canvas.hpp"

namespace bipednav::viz {

// How a legend entry shows its layer.
enum class LegendMark {
  kLine,   // a path
  kBox,    // an area (cells, obstacles)
  kRing,   // a circle outline (goals)
  kDot,    // a filled disc (points, markers)
  kArrow,  // a pose (robot, start)
  kCross,  // a contact
};

struct LegendEntry {
  std::string label;
  Color color;
  LegendMark mark = LegendMark::kLine;
  Color fill = colors::kNone;  // kBox: the inside (none: the colour); kRing: the inside (none: empty)
};

struct LegendStyle {
  double font_px = 12.0;
  double row_px = 18.0;
  double swatch_px = 24.0;
  double pad_px = 6.0;
};

// The size a legend of these entries takes.
PixelRect legend_extent(const Canvas& canvas, const std::vector<LegendEntry>& entries, const LegendStyle& style = {});
// Draws the legend with its top-left corner at (x_px, y_px) on a white box; returns its rectangle.
PixelRect draw_legend(Canvas& canvas, double x_px, double y_px, const std::vector<LegendEntry>& entries,
                      const LegendStyle& style = {});

// The longest "round" length (1, 2 or 5 times a power of ten, metres) not longer than max_m.
double scale_bar_length_m(double max_m);
// A scale bar at the canvas' scale: a bar of scale_bar_length_m(max_px / pixels_per_m) with its
// length written under it, its left end at (x_px, y_px); returns its rectangle.
PixelRect draw_scale_bar(Canvas& canvas, double x_px, double y_px, double max_px);

// The room a colour ramp takes below a legend: with_legend_bands' extra_h_px for draw_color_ramp.
inline constexpr double kColorRampRoomPx = 60.0;
// A colour ramp from `lo` to `hi` (at most 140 px wide, 12 px tall) with its end labels and a
// caption above it (e.g. heights), at the top of `area` (draw_title_and_legend's free rest);
// returns its rectangle.
PixelRect draw_color_ramp(Canvas& canvas, const PixelRect& area, Color lo, Color hi, const std::string& lo_label,
                          const std::string& hi_label, const std::string& caption);

// A single-panel figure's frame: `params` with a title band above the world's window and a
// legend column right of it wide enough for `entries`, a scale bar and `extra_h_px` more (e.g. a
// colour ramp), with room below the window when the column is taller than it.
CanvasParams with_legend_bands(CanvasParams params, const std::vector<LegendEntry>& entries, double extra_h_px = 0.0);
// Draws the title in the top band and the legend and a scale bar in the right band of a canvas
// made from with_legend_bands(); returns the free rest of the legend column (for the extra).
PixelRect draw_title_and_legend(Canvas& canvas, const std::string& title, const std::vector<LegendEntry>& entries);

}  // namespace bipednav::viz
