#pragma once

#include <random>
#include <vector>

#include "bipednav/planning/local/teb_optimizer.hpp"

namespace bipednav::planning::local::test {

// A random problem of the solver comparisons: a start speed, a goal about 3 m ahead, a via point on
// even trials and a band twice as slow as time-optimal on every third, drawn from rng in this order.
struct TebTrial {
  TebProblemInput in;
  TebBand band;
};

inline TebTrial random_teb_trial(int trial, std::mt19937& rng, std::uniform_real_distribution<double>& u,
                                 const std::vector<Obstacle>& obs, const TebLimits& lim, const TebBandParams& bp) {
  TebTrial t;
  t.in.obstacles = &obs;
  t.in.start_velocity.linear_x = 0.2 + 0.2 * u(rng);
  const Pose2 goal{3.0 + 0.5 * u(rng), 0.8 * u(rng), 0.5 * u(rng)};
  if (trial % 2 == 0) t.in.via_points = {{1.5, 0.5 + 0.2 * u(rng)}};
  t.band = init_band({0, 0, 0.3 * u(rng)}, t.in.via_points, goal, lim, bp);
  if (trial % 3 == 0)
    for (double& dt : t.band.dt_s) dt *= 2.0;  // far from time-optimal
  return t;
}

}  // namespace bipednav::planning::local::test
