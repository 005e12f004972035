#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/viz/figure_layout.hpp"
#include "bipednav/viz/figure_legend.hpp"

namespace bipednav::runner {

// A figure like the thesis' Fig. 6.1, one panel at the end of the run and one per replanning
// snapshot, laid out for the world's aspect ratio (viz::figure_layout) with a legend and a scale
// bar: the world (light grey, for reference) and its moving obstacles (orange), global-map
// obstacles (black), local-map obstacles (purple) and inflation (blue), the global path (red), the
// local trajectory (green, named after `local_planner`: "teb" or "tracker"), the travelled path
// (teal), the start (grey arrow), the goals (rings of the goal tolerance), the robot (black arrow)
// and every contact (red crosses, the first one larger).
void write_run_figure(const std::filesystem::path& file, const sim::Scenario& scenario, const RunResult& run,
                      const std::string& local_planner = "teb");

// The legend entries of that figure: the layers it shows (moving obstacles and the contacts only
// when the run has them).
std::vector<viz::LegendEntry> run_figure_legend(const sim::Scenario& scenario, const RunResult& run,
                                                const std::string& local_planner);
// The points a panel at time t_s marks as contacts: every contact of the run up to t_s, oldest
// first (the run's first_collision when it has no contact list, as a footstep run).
std::vector<Eigen::Vector2d> contact_marks(const RunResult& run, double t_s);
// "TEB" or "path tracker" for a local planner's name.
std::string local_planner_label(const std::string& local_planner);

}  // namespace bipednav::runner
