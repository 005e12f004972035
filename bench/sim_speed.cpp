#include "bench/sim_speed.hpp"

#include <algorithm>
#include <ctime>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <utility>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/common/progress.hpp"
#include "bipednav/io/robot_profile_yaml.hpp"
#include "bipednav/sim/simulation.hpp"

namespace bipednav::bench {
namespace {

using sim::Box;
using sim::Cylinder;
using sim::Geometry;

// A 12 x 10 m room, 2.5 m walls, with pillars, crates and one box walking a square.
sim::World benchmark_world() {
  sim::World w;
  w.name = "bench_room";
  const double lx = 12.0, ly = 10.0, t = 0.1, h = 2.5;
  w.statics.push_back({"wall_n", make_se3(0, ly / 2, h / 2, 0, 0, 0), Box{{lx, t, h}}});
  w.statics.push_back({"wall_s", make_se3(0, -ly / 2, h / 2, 0, 0, 0), Box{{lx, t, h}}});
  w.statics.push_back({"wall_e", make_se3(lx / 2, 0, h / 2, 0, 0, 0), Box{{t, ly, h}}});
  w.statics.push_back({"wall_w", make_se3(-lx / 2, 0, h / 2, 0, 0, 0), Box{{t, ly, h}}});
  const double pillars[][2] = {{3, 2}, {-3, 2}, {3, -2}, {-3, -2}, {0, 3.5}, {0, -3.5}};
  for (const auto& p : pillars)
    w.statics.push_back({"pillar", make_se3(p[0], p[1], 1.0, 0, 0, 0), Cylinder{0.15, 2.0}});
  const double crates[][3] = {{4.5, 0, 0.3}, {-4.5, 0.5, 0.7}, {1.5, -4, 0.0}, {-1.5, 4, 1.2}};
  for (const auto& c : crates)
    w.statics.push_back({"crate", make_se3(c[0], c[1], 0.4, 0, 0, c[2]), Box{{0.8, 0.6, 0.8}}});
  sim::Actor mover;
  mover.name = "mover";
  mover.parts.push_back({"box", SE3::Identity(), Box{{0.15, 0.15, 2.0}}});
  const double s = 1.0;
  for (int i = 0; i <= 4; ++i) {
    const double xy[5][2] = {{s, s}, {-s, s}, {-s, -s}, {s, -s}, {s, s}};
    mover.trajectory.push_back({4.0 * i, make_se3(xy[i][0] + 2.0, xy[i][1], 1.0, 0, 0, 0)});
  }
  w.actors.push_back(mover);
  return w;
}

// Digit as in config/digit.yaml (used when no --robot file is given).
RobotProfile digit_profile() {
  RobotProfile p;
  p.name = "digit";
  p.kind = "walker";
  p.footprint_radius_m = 0.35;
  p.height_m = 1.6;
  p.limits.max_vel_x_mps = 0.5;
  p.limits.max_vel_x_backwards_mps = 0.25;
  p.limits.max_vel_theta_radps = 0.6;
  p.limits.acc_lim_x_mps2 = 0.5;
  p.limits.acc_lim_theta_radps2 = 1.0;
  p.tracking_time_constant_s = 0.3;
  p.sway_amplitude_m = 0.03;
  p.step_frequency_hz = 2.0;
  const double d45 = std::numbers::pi / 4;
  p.sensors = {{"lidar", "vlp16", 0, 0, 1.474, 0, 0, 0},
               {"depth_front", "d430", 0.1, 0, 0.95, 0, d45, 0},
               {"depth_back", "d430", -0.1, 0, 0.95, 0, d45, std::numbers::pi}};
  return p;
}

}  // namespace

nlohmann::json run_sim_bench(const SimBenchOptions& o) {
  require(o.duration_s > 0 && o.duration_s <= 3600, "--duration", "in (0, 3600] s");
  const RobotProfile robot = o.robot_file.empty() ? digit_profile() : io::load_robot_profile(o.robot_file);
  sim::SimulationParams params;
  params.seed = 1;
  params.raycaster.threads = 1;
  params.enable_lidar = o.sensors != "depth";
  params.enable_depth = o.sensors != "lidar";
  params.depth.renderer = o.renderer;
  sim::Simulation simulation(benchmark_world(), robot, Pose2{-2.0, 0.0, 0.0}, params);
  const auto steps = static_cast<std::size_t>(std::llround(o.duration_s / params.step_s));
  ProgressBar progress("bench sim", steps, o.progress);
  std::size_t lidar_points = 0;
  const Stopwatch wall;
  const std::clock_t cpu0 = std::clock();
  // Held like a consumer holds its latest data.
  std::optional<PointCloud> latest_lidar;
  std::vector<DepthCloud> latest_depth;
  for (std::size_t i = 0; i < steps; ++i) {
    // A slow circle through the room (radius 2 m at 0.4 m/s).
    SensorFrame f = simulation.step(Twist{0.4, 0.0, 0.2});
    if (f.lidar) lidar_points += f.lidar->size();
    // The data replaced goes back to the simulator, whose next clouds reuse its buffers (as the
    // closed loop's runner does: no allocation and page faults per image).
    SensorFrame spent;
    if (f.lidar) spent.lidar = std::exchange(latest_lidar, std::move(f.lidar));
    if (!f.depth.empty()) spent.depth = std::exchange(latest_depth, std::move(f.depth));
    simulation.recycle(std::move(spent));
    progress.update(i + 1);
  }
  const double wall_ms = wall.elapsed_ms();
  const double cpu_ms = 1e3 * static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  progress.finish();
  const sim::SimulationStats& st = simulation.stats();
  const double cpu_rtf = simulation.now_s() / (cpu_ms * 1e-3);
  const auto depth_cameras =
      std::count_if(robot.sensors.begin(), robot.sensors.end(), [](const SensorMount& m) { return m.type == "d430"; });
  const double wall_rtf = simulation.now_s() / (wall_ms * 1e-3);
  nlohmann::json j;
  j["robot"] = robot.name;
  // What is simulated (the benchmark: nothing is cached across frames, every ray is cast).
  j["sensors"] = {
      {"lidar", params.enable_lidar ? nlohmann::json{{"rate_hz", params.lidar.rate_hz},
                                                     {"rings", params.lidar.rings},
                                                     {"columns", params.lidar.columns},
                                                     {"range_noise_stddev_m", params.lidar.range_noise_stddev_m},
                                                     {"per_column_firing_time", true}}
                                    : nlohmann::json(nullptr)},
      {"depth_cameras", params.enable_depth ? nlohmann::json{{"count", depth_cameras},
                                                             {"rate_hz", params.depth.rate_hz},
                                                             {"width", params.depth.width},
                                                             {"height", params.depth.height},
                                                             {"noise_coeff_per_m", params.depth.noise_coeff_per_m},
                                                             {"renderer", params.depth.renderer}}
                                            : nlohmann::json(nullptr)}};
  j["simulated_s"] = simulation.now_s();
  // The goal is measured on CPU time: simulated seconds per CPU second of this process
  // (std::clock), with the simulation on one thread (Embree threads = 1). On a shared machine
  // wall time also counts waiting for a core; it is reported alongside.
  j["measured_on"] = "process CPU time, one thread";
  j["real_time_factor_rtf"] = cpu_rtf;
  j["cpu_ms"] = cpu_ms;
  j["cpu_real_time_factor_rtf"] = cpu_rtf;
  j["wall_ms"] = wall_ms;
  j["wall_real_time_factor_rtf"] = wall_rtf;
  j["lidar_sweeps"] = st.lidar_sweeps;
  j["lidar_points_per_sweep"] = st.lidar_sweeps ? static_cast<double>(lidar_points) / st.lidar_sweeps : 0.0;
  j["lidar_sweep_wall_ms"] = st.lidar_sweeps ? st.lidar_ms / st.lidar_sweeps : 0.0;
  j["depth_images"] = st.depth_images;
  j["depth_image_wall_ms"] = st.depth_images ? st.depth_ms / st.depth_images : 0.0;
  j["other_wall_ms_per_step"] = (wall_ms - st.lidar_ms - st.depth_ms) / static_cast<double>(st.steps);
  j["threads"] = params.raycaster.threads;
  j["goal_rtf"] = 20;
  j["meets_goal"] = cpu_rtf >= 20.0;
  return j;
}

}  // namespace bipednav::bench
