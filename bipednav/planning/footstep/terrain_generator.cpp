#include "bipednav/planning/footstep/terrain_generator.hpp"

#include <cmath>
#include <numbers>

#include "bipednav/common/error.hpp"
#include "bipednav/common/rng.hpp"

namespace bipednav::planning::footstep {

void TerrainGeneratorParams::validate() const {
  require(size_m > 0.2, "size_m", "> 0.2 m");
  require(resolution_m > 0.0 && resolution_m < size_m / 10, "resolution_m", "in (0, size_m / 10)");
  require(bars >= 0 && platforms >= 0 && blocks >= 0, "bars/platforms/blocks", ">= 0");
  require(bar_height_min_m <= bar_height_max_m && platform_height_min_m <= platform_height_max_m &&
              block_height_min_m <= block_height_max_m,
          "*_height_min_m", "<= the matching *_height_max_m");
}

namespace {

// Raises every cell whose centre lies in the rotated rectangle to at least `h`.
void stamp_box(mapping::Heightmap& m, const Pose2& centre, double len, double wid, double h) {
  const auto& g = m.geometry();
  const double c = std::cos(centre.theta), s = std::sin(centre.theta);
  const double ext = 0.5 * (std::abs(c) * len + std::abs(s) * wid) + g.resolution_m,
               eyt = 0.5 * (std::abs(s) * len + std::abs(c) * wid) + g.resolution_m;
  const auto lo = g.world_to_cell_unbounded(centre.x - ext, centre.y - eyt);
  const auto hi = g.world_to_cell_unbounded(centre.x + ext, centre.y + eyt);
  if (!lo || !hi) return;
  for (int y = std::max(0, lo->y); y <= std::min(g.height - 1, hi->y); ++y) {
    for (int x = std::max(0, lo->x); x <= std::min(g.width - 1, hi->x); ++x) {
      const auto p = g.cell_center(x, y);
      const double dx = p.x() - centre.x, dy = p.y() - centre.y;
      if (std::abs(c * dx + s * dy) <= len / 2 && std::abs(-s * dx + c * dy) <= wid / 2 && m.height(x, y) < h)
        m.set(x, y, static_cast<float>(h), 0.0f);
    }
  }
}

}  // namespace

mapping::Heightmap random_terrain(const TerrainGeneratorParams& p, std::uint64_t seed) {
  p.validate();
  const int n = static_cast<int>(std::lround(p.size_m / p.resolution_m));
  mapping::Heightmap m({n, n, p.resolution_m, 0.0, 0.0});
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) m.set(x, y, 0.0f, 0.0f);
  Rng rng(seed);
  const auto place = [&] {
    return Pose2{rng.uniform(0, p.size_m), rng.uniform(0, p.size_m), rng.uniform(0, std::numbers::pi)};
  };
  for (int i = 0; i < p.platforms; ++i) {
    const Pose2 c = place();
    stamp_box(m, c, rng.uniform(p.platform_size_min_m, p.platform_size_max_m),
              rng.uniform(p.platform_size_min_m, p.platform_size_max_m),
              rng.uniform(p.platform_height_min_m, p.platform_height_max_m));
  }
  for (int i = 0; i < p.bars; ++i) {
    const Pose2 c = place();
    stamp_box(m, c, rng.uniform(p.bar_length_min_m, p.bar_length_max_m),
              rng.uniform(p.bar_width_min_m, p.bar_width_max_m), rng.uniform(p.bar_height_min_m, p.bar_height_max_m));
  }
  for (int i = 0; i < p.blocks; ++i) {
    const Pose2 c = place();
    stamp_box(m, c, rng.uniform(p.block_size_min_m, p.block_size_max_m),
              rng.uniform(p.block_size_min_m, p.block_size_max_m),
              rng.uniform(p.block_height_min_m, p.block_height_max_m));
  }
  return m;
}

namespace {

// A body pose is usable when both stances are flat and nothing within the body's reach rises
// above the lowest body part (so the first and last steps cannot be blocked).
bool pose_clear(const mapping::Heightmap& m, const FootstepPlanner& planner, const Pose2& body) {
  const auto& g = m.geometry();
  const auto& b = planner.lattice().actions().body;
  const double reach = b.arm_offset_m + b.arm_width_m + 0.05;
  const auto c = g.world_to_cell(body.x, body.y);
  if (!c) return false;
  const int r = static_cast<int>(std::ceil(reach / g.resolution_m));
  float lo = 1e9f, hi = -1e9f;
  for (int y = c->y - r; y <= c->y + r; ++y) {
    for (int x = c->x - r; x <= c->x + r; ++x) {
      if (!g.in_bounds(x, y)) return false;  // keep the whole body on the map
      lo = std::min(lo, m.height(x, y));
      hi = std::max(hi, m.height(x, y));
    }
  }
  return hi - lo <= 1e-6;
}

}  // namespace

std::vector<PlanningProblem> random_problems(const mapping::Heightmap& map, const FootstepPlanner& planner,
                                             std::size_t count, double min_dist_m, double max_dist_m,
                                             std::uint64_t seed) {
  Rng rng(seed);
  const auto& g = map.geometry();
  std::vector<PlanningProblem> out;
  for (int attempt = 0; out.size() < count && attempt < 200000; ++attempt) {
    const Pose2 s{g.origin_x_m + rng.uniform(0, g.size_x_m()), g.origin_y_m + rng.uniform(0, g.size_y_m()),
                  rng.uniform(-std::numbers::pi, std::numbers::pi)};
    const Pose2 e{g.origin_x_m + rng.uniform(0, g.size_x_m()), g.origin_y_m + rng.uniform(0, g.size_y_m()),
                  rng.uniform(-std::numbers::pi, std::numbers::pi)};
    const double d = distance(s, e);
    if (d < min_dist_m || d > max_dist_m) continue;
    if (pose_clear(map, planner, s) && pose_clear(map, planner, e)) out.push_back({s, e});
  }
  return out;
}

}  // namespace bipednav::planning::footstep
