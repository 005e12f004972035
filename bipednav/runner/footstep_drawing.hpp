#pragma once

#include <string>
#include <vector>

#include "bipednav/mapping/heightmap.hpp"
#include "bipednav/planning/footstep/action_set.hpp"
#include "bipednav/planning/footstep/footstep_types.hpp"
#include "bipednav/viz/canvas.hpp"

namespace bipednav::runner {

// A canvas showing a whole grid (at most ~800 px on the longer side).
viz::CanvasParams canvas_for(const mapping::GridGeometry& g);
// The heights a heightmap's grey levels span.
struct HeightRange {
  double lo_m = 0.0, hi_m = 0.0;
};
// Heights as grey levels (darker = higher, as in the footstep reference's figures); unobserved
// cells pink. Returns the range the greys span (for draw_footstep_legend).
HeightRange draw_heightmap(viz::Canvas& c, const mapping::Heightmap& map);
// Footprints of placed feet: left blue, right red, the landings of 3D actions (step-over / onto /
// down, T-step) outlined in orange. `actions[i]` leads to `steps[i + 1]` (may be shorter).
void draw_footsteps(viz::Canvas& c, const planning::footstep::BodyModel& body,
                    const std::vector<planning::footstep::Footstep>& steps, const std::vector<std::string>& actions,
                    double fill_alpha = 0.35, double line_px = 1.5);
// The goal: a green circle with its heading.
void draw_goal(viz::Canvas& c, const Pose2& goal);
// The start: a grey circle with its heading.
void draw_start(viz::Canvas& c, const Pose2& start);

// A footstep figure's canvas: the grid's extent with a title band and a legend column (legend,
// scale bar, height ramp).
viz::CanvasParams footstep_canvas(const mapping::GridGeometry& g, bool with_path);
// Its title, legend (feet, start, goal, and with_path the body path and contacts), scale bar and
// the height ramp of `heights`.
void draw_footstep_legend(viz::Canvas& c, const std::string& title, const HeightRange& heights, bool with_path);

}  // namespace bipednav::runner
