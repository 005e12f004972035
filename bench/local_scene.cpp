#include "bench/local_scene.hpp"

#include <algorithm>
#include <cmath>
#include <ctime>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/cpu_time.hpp"
#include "bipednav/common/rng.hpp"
#include "bipednav/planning/local/teb_planner.hpp"

namespace bipednav::bench {

void stamp_disc(mapping::Costmap2D& m, double x, double y, double r, double inscribed) {
  const auto& g = m.geometry();
  const int reach = static_cast<int>(std::ceil((r + inscribed) / g.resolution_m)) + 1;
  const auto c0 = g.world_to_cell_unbounded(x, y);
  if (!c0) return;
  for (int cy = c0->y - reach; cy <= c0->y + reach; ++cy) {
    for (int cx = c0->x - reach; cx <= c0->x + reach; ++cx) {
      if (!g.in_bounds(cx, cy)) continue;
      const auto c = g.cell_center(cx, cy);
      const double d = std::hypot(c.x() - x, c.y() - y);
      if (d <= r)
        m.set_cost(cx, cy, mapping::kLethal);
      else if (d <= r + inscribed && m.cost(cx, cy) < mapping::kInscribed)
        m.set_cost(cx, cy, mapping::kInscribed);
    }
  }
}

namespace {

// The q-quantile of a sorted, non-empty sample.
double quantile(const std::vector<double>& sorted, double q) {
  return sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(q * static_cast<double>(sorted.size())))];
}

}  // namespace

LocalBenchScene make_local_bench_scene(int n_obstacles, std::uint64_t seed) {
  LocalBenchScene s;
  mapping::GridGeometry g;
  g.width = g.height = 160;
  g.resolution_m = 0.05;
  g.origin_x_m = g.origin_y_m = -4.0;
  s.costmap = mapping::Costmap2D(g, mapping::kFree);
  s.start = {-3.0, 0.0, 0.0};
  for (int i = 0; i <= 60; ++i) s.plan.poses.push_back({-3.0 + 0.1 * i, 0.0, 0.0});
  Rng rng(seed);
  for (int placed = 0, tries = 0; placed < n_obstacles && tries < 100 * (n_obstacles + 1); ++tries) {
    const double x = rng.uniform(-3.8, 3.8), y = rng.uniform(-3.8, 3.8);
    // Keep the start and the goal clear.
    if (std::hypot(x - s.start.x, y - s.start.y) < 0.8 || std::hypot(x - 3.0, y) < 0.8) continue;
    stamp_disc(s.costmap, x, y, rng.uniform(0.02, 0.08), 0.2);
    ++placed;
  }
  return s;
}

LocalBenchStats run_local_bench(const LocalBenchScene& scene, const planning::local::TebParams& params, int cycles) {
  planning::local::TebPlanner planner(params);
  LocalBenchStats st;
  std::vector<double> ms, cpu;
  Pose2 p = scene.start;
  Twist v;
  const double dt = params.control_period_s;
  for (int i = 0; i < cycles; ++i) {
    Stopwatch sw;
    const double c0 = thread_cpu_ms();
    const auto r = planner.compute(p, v, scene.plan, scene.costmap, i * dt);
    cpu.push_back(thread_cpu_ms() - c0);
    ms.push_back(sw.elapsed_ms());
    if (r.result.ok()) ++st.success_cycles;
    st.obstacles = static_cast<int>(planner.obstacles().size());
    if (r.goal_reached) break;
    // Unicycle integration of the command.
    v = r.cmd;
    p = p * Pose2{v.linear_x * dt, 0.0, v.angular_z * dt};
  }
  st.cycles = static_cast<int>(ms.size());
  std::sort(ms.begin(), ms.end());
  std::sort(cpu.begin(), cpu.end());
  st.median_ms = quantile(ms, 0.5);
  st.p99_ms = quantile(ms, 0.99);
  st.max_ms = ms.back();
  st.cpu_median_ms = quantile(cpu, 0.5);
  st.cpu_p99_ms = quantile(cpu, 0.99);
  return st;
}

}  // namespace bipednav::bench
