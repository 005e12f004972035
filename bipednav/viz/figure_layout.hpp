#pragma once

#include <cstddef>
#include <vector>

#include "bipednav/viz/canvas.hpp"

namespace bipednav::viz {

// Where the panels of a multi-panel top-view figure go (run.png: the end of the run and the
// replanning moments), from the world's extent and the panel count alone, so that panels of any
// aspect ratio (a 30 x 6 m corridor, a 5 x 15 m BARN field) neither overlap nor leave the picture.
struct FigureLayoutParams {
  double max_width_px = 1800.0, max_height_px = 1300.0;  // the picture's size, unless pixels_per_m hits its minimum
  double min_pixels_per_m = 8.0, max_pixels_per_m = 120.0;
  double margin_px = 12.0;   // around everything
  double header_px = 28.0;   // the figure's title, across the top
  double title_px = 22.0;    // each panel's title, above it
  double gap_px = 14.0;      // between panels, and before the legend column
  double legend_w_px = 0.0;  // the legend column right of the panels (0: none)
  double legend_h_px = 0.0;  // its height (the picture is at least this tall below the header)

  void validate() const;
};

struct FigureLayout {
  double pixels_per_m = 0.0;
  int columns = 0, rows = 0;
  int width_px = 0, height_px = 0;
  PixelRect header;
  std::vector<PixelRect> titles;  // one per panel, directly above it
  std::vector<PixelRect> panels;  // one per panel: the world's window at pixels_per_m
  PixelRect legend;               // the legend column (w 0 without one)
};

// The layout of `panels` panels each showing a world window of width_m x height_m: the column
// count that gives the largest scale within the size limits, then the rows filled left to right.
// Throws ParamError for a non-finite or non-positive extent or no panels.
FigureLayout figure_layout(double width_m, double height_m, std::size_t panels, const FigureLayoutParams& params = {});

// Whether two rectangles share interior points (touching edges do not count).
bool overlap(const PixelRect& a, const PixelRect& b);

}  // namespace bipednav::viz
