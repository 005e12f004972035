#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "bipednav/planning/footstep/action_set.hpp"
#include "bipednav/planning/footstep/footstep_types.hpp"

namespace bipednav::planning::footstep {

// One cell of an inverse heightmap (section V-C): a lattice offset from the stance foot and
// the lowest height, relative to the stance sole, that any body part reaches over it.
struct IhmCell {
  std::int16_t dx = 0;
  std::int16_t dy = 0;
  float min_height_m = 0.0f;
};

// A band of an inverse heightmap's cells with its bounding box and lowest height, so a whole
// band can be cleared at once when the terrain under its box stays below that height.
struct IhmLayer {
  std::vector<IhmCell> cells;  // complete type first: clang rejects size() on an incomplete one
  int min_dx = 0, max_dx = 0, min_dy = 0, max_dy = 0;
  float min_height_m = 0.0f;
};

// An inverse heightmap split into height bands (feet, legs, body): most terrain never reaches
// the body, so its many cells are rarely compared one by one.
struct InverseHeightmap {
  std::vector<IhmLayer> layers;
  std::size_t size() const {
    std::size_t n = 0;
    for (const auto& l : layers) n += l.cells.size();
    return n;
  }
};

// An oriented rectangle in the stance foot's frame (metres, radians).
struct Rect {
  double cx = 0, cy = 0, heading = 0, half_x = 0, half_y = 0;
};

// Calls `visit(dx, dy)` for every lattice cell (resolution `res`, stance foot at cell (0, 0),
// lattice rotated by `theta` relative to the rect's frame) whose centre lies within the rect
// grown by `grow_m`.
template <typename Visit>
void rasterize_rect(const Rect& r, double theta, double res, double grow_m, Visit&& visit) {
  const double ct = std::cos(theta), st = std::sin(theta);
  const double cx = ct * r.cx - st * r.cy, cy = st * r.cx + ct * r.cy;  // centre in the lattice frame
  const double h = theta + r.heading, ch = std::cos(h), sh = std::sin(h);
  const double hx = r.half_x + grow_m, hy = r.half_y + grow_m;
  const double ext_x = std::abs(ch) * hx + std::abs(sh) * hy, ext_y = std::abs(sh) * hx + std::abs(ch) * hy;
  const int x0 = static_cast<int>(std::floor((cx - ext_x) / res)), x1 = static_cast<int>(std::ceil((cx + ext_x) / res));
  const int y0 = static_cast<int>(std::floor((cy - ext_y) / res)), y1 = static_cast<int>(std::ceil((cy + ext_y) / res));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double px = x * res - cx, py = y * res - cy;
      const double u = ch * px + sh * py, v = -sh * px + ch * py;  // into the rect's frame
      if (std::abs(u) <= hx && std::abs(v) <= hy) visit(x, y);
    }
  }
}

// The inverse heightmap of one action for one stance foot, aligned to a stance heading
// `theta`: the swept volume of the body model (swing foot and leg from the via point to the
// landing pose, the body between the feet, the trailing foot up to the next via point),
// projected onto the lattice. The stance and landing soles are excluded: flatness and eq. 4
// check those. `swing_lift_m` raises the downward phase's swing foot and leg by that much: a
// swing foot that starts higher than the stance foot (the trailing foot still on the step the
// stance foot came down from) keeps its lifted height until it drops onto the landing
// (sim::HumanoidWalker::step); 0 is the via point configuration of every other step.
// `stance_landed`: the stance foot is where the robot really stands (a search's start), so its
// lift-off sweeps only its own sole; at a planned foothold the lift-off also covers the cells
// within half a cell of the sole, a margin for where the foot will really land.
InverseHeightmap build_inverse_heightmap(const FootstepAction& action, const BodyModel& body, Foot stance, double theta,
                                         double res, double swing_lift_m = 0.0, bool stance_landed = false);

// Lattice offsets of a foot sole with heading `theta` centred on cell (0, 0), the sole grown by
// `grow_m` on every side.
std::vector<std::pair<std::int16_t, std::int16_t>> footprint_cells(const BodyModel& body, double theta, double res,
                                                                   double grow_m = 0.0);

}  // namespace bipednav::planning::footstep
