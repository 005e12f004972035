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
// Heights as grey levels (darker = higher, as in the footstep reference's figures); unobserved
// cells pink.
void draw_heightmap(viz::Canvas& c, const mapping::Heightmap& map);
// Footprints of placed feet: left blue, right red, the landings of 3D actions (step-over / onto /
// down, T-step) outlined in orange. `actions[i]` leads to `steps[i + 1]` (may be shorter).
void draw_footsteps(viz::Canvas& c, const footstep::BodyModel& body, const std::vector<footstep::Footstep>& steps,
                    const std::vector<std::string>& actions, double fill_alpha = 0.35, double line_px = 1.5);
// The goal: a green circle with its heading.
void draw_goal(viz::Canvas& c, const Pose2& goal);

}  // namespace bipednav::runner
