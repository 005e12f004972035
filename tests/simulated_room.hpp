#pragma once

// A closed room for simulated LiDAR sweeps (tests of the sweeps' ring and time reconstruction and
// of odometry on recorded sweeps): every beam of a VLP-16 inside returns.
#include <functional>
#include <optional>
#include <vector>

#include "bipednav/common/point_cloud.hpp"
#include "bipednav/common/se3.hpp"
#include "bipednav/sim/raycaster.hpp"
#include "bipednav/sim/vlp16.hpp"
#include "bipednav/sim/world.hpp"

namespace bipednav::test {

// Floor, ceiling, four walls 40 x 30 m, and pillars and boxes for edges and planes in every direction.
inline sim::World lidar_room() {
  sim::World w;
  const auto box = [&](const char* name, double x, double y, double z, double sx, double sy, double sz) {
    w.statics.push_back({name, make_se3(x, y, z, 0, 0, 0), sim::Box{{sx, sy, sz}}});
  };
  box("floor", 0, 0, -0.05, 40, 30, 0.1);
  box("ceiling", 0, 0, 6.05, 40, 30, 0.1);
  box("north", 0, 15, 3, 40, 0.2, 6);
  box("south", 0, -15, 3, 40, 0.2, 6);
  box("east", 20, 0, 3, 0.2, 30, 6);
  box("west", -20, 0, 3, 0.2, 30, 6);
  box("pillar", 3, 2, 3, 0.5, 0.5, 6);
  box("pillar_2", 8, -4, 3, 0.6, 0.6, 6);
  box("pillar_3", -5, 6, 3, 0.4, 0.4, 6);
  box("crate", 6, 5, 0.5, 1.5, 1.0, 1.0);
  box("crate_2", -3, -6, 0.75, 1.0, 2.0, 1.5);
  box("shelf", 12, 9, 1.0, 4.0, 0.5, 2.0);
  return w;
}

// `n` sweeps of the simulator's VLP-16 (range noise included) while the sensor follows
// T_world_sensor(t); `T_world_end` receives the sensor's pose at each sweep's end.
inline std::vector<PointCloud> simulated_vlp16_sweeps(const sim::World& w, const std::function<SE3(double)>& pose_at,
                                                      std::size_t n, std::vector<SE3>* T_world_end = nullptr) {
  const sim::RayCaster caster(w);
  sim::Vlp16 lidar(sim::Vlp16Params{}, "lidar", 5);
  std::vector<PointCloud> sweeps;
  for (double t = 0.01; sweeps.size() < n; t += 0.01) {
    std::optional<PointCloud> s = lidar.fire_until(t, caster, pose_at);
    if (!s) continue;
    sweeps.push_back(std::move(*s));
    if (T_world_end) T_world_end->push_back(pose_at(static_cast<double>(sweeps.size()) / lidar.params().rate_hz));
  }
  return sweeps;
}

}  // namespace bipednav::test
