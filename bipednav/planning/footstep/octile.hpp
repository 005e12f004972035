#pragma once

#include <numbers>

namespace bipednav::planning::footstep {

// The 8-connected neighbourhood of the heuristics' grid graphs (0..3 orthogonal, 4..7 diagonal).
inline constexpr int kOctileDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
inline constexpr int kOctileDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};

// Octile steps scaled by the worst octile/Euclidean ratio (1.0824) keep a graph distance below
// the length of any continuous path. (A 16-connected graph, worst ratio 1.0275, was tried: its
// tighter distances changed nao_stairs' epsilon-3 plans in the loop into one that brushed the
// side wall with an arm; kept 8-connected.)
inline double octile_step_m(int k, double res) {
  constexpr double kOctileToEuclid = 1.0 / 1.0823922;
  return (k < 4 ? res : res * std::numbers::sqrt2) * kOctileToEuclid;
}

}  // namespace bipednav::planning::footstep
