#include "bipednav/mapping/obstacle_layer.hpp"

#include <gtest/gtest.h>

#include "bipednav/common/rng.hpp"

namespace bipednav::mapping {
namespace {

// Observations of one sensor from one cell (obstacle and ground returns, consecutive frames) share
// their clearing rays when no cell has a height band. The grid and the changed box must be those
// of tracing every ray: compared against a layer whose rays are not shared (a band given to a cell
// that is not an obstacle switches the sharing off without changing any ray's effect).
TEST(ObstacleLayer, SharedRaysClearAsTracingEveryRay) {
  const GridGeometry g{80, 60, 0.05, -2.0, -1.5};
  Rng rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    Costmap2D shared(g, kUnknown), traced(g, kUnknown);
    for (std::size_t i = 0; i < g.size(); ++i)  // some obstacles to clear
      if (rng.uniform(0, 1) < 0.2) shared.data()[i] = traced.data()[i] = kLethal;
    ObstacleLayerParams params;
    params.raytrace_max_range_m = 1.5;  // some rays are clipped (their end cell is then freed)
    ObstacleLayer a(params), b(params);
    b.include_band(traced, 79, 59, HeightBand{0.0f, 1.0f}, true);
    traced.data()[g.index(79, 59)] = kFree;  // a banded cell that is no obstacle: no ray depends on it
    shared.data()[g.index(79, 59)] = kFree;
    std::vector<Observation> obs;
    const Eigen::Vector3d origin(rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), 0.3);
    for (int k = 0; k < 6; ++k) {
      Observation o;
      // The same cell (0.05 m) for most, a neighbouring one for some.
      o.origin_map = origin + Eigen::Vector3d(rng.uniform(0, 0.01), rng.uniform(0, 0.01), 0.0) +
                     (k == 4 ? Eigen::Vector3d(0.05, 0.0, 0.0) : Eigen::Vector3d::Zero());
      o.marking = k % 2 == 0;
      o.max_range_m = k == 5 ? 1.0 : 3.0;
      for (int i = 0; i < 300; ++i)
        o.points_map.emplace_back(static_cast<float>(rng.uniform(-2.2, 2.2)),
                                  static_cast<float>(rng.uniform(-1.7, 1.7)),
                                  static_cast<float>(rng.uniform(0.0, 1.0)));
      obs.push_back(o);
    }
    for (int round = 0; round < 2; ++round) {  // twice: stamps of an earlier update must not count
      const CellRect ca = a.update(shared, obs), cb = b.update(traced, obs);
      EXPECT_EQ(shared.data(), traced.data());
      EXPECT_EQ(ca.x0, cb.x0);
      EXPECT_EQ(ca.y0, cb.y0);
      EXPECT_EQ(ca.x1, cb.x1);
      EXPECT_EQ(ca.y1, cb.y1);
    }
  }
}

}  // namespace
}  // namespace bipednav::mapping
