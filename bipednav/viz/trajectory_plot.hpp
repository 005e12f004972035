#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "bipednav/viz/canvas.hpp"

namespace bipednav::viz {

// One trajectory of a plot: its x, y positions (m) in drawing order.
struct PlotLine {
  std::string label;
  Color color = colors::kBlack;
  std::vector<Eigen::Vector2d> xy;
};

// A top view of trajectories (estimate against ground truth): the lines fitted into a picture of
// about `size_px` on its longer side with equal scales on both axes, each line's start marked,
// a legend (label and colour per line), a scale bar of a round length (1, 2 or 5 x 10^k m) and
// the title. Throws Error when no line has a point, FileError when the file cannot be written.
void write_trajectory_plot(const std::filesystem::path& file, const std::vector<PlotLine>& lines,
                           const std::string& title, double size_px = 800.0);

}  // namespace bipednav::viz
