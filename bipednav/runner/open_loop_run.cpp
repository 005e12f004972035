#include "bipednav/runner/open_loop_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/progress.hpp"
#include "bipednav/sim/world_drawing.hpp"
#include "bipednav/viz/canvas.hpp"
#include "bipednav/viz/figure_legend.hpp"

namespace bipednav::runner {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// True robot poses over time, sampled at every step end, linearly interpolated in between.
struct PoseTrack {
  std::vector<double> t_s;
  std::vector<Pose2> pose;

  void add(double t, const Pose2& p) { t_s.push_back(t), pose.push_back(p); }
  Pose2 at(double t) const {
    const auto it = std::lower_bound(t_s.begin(), t_s.end(), t);
    if (it == t_s.begin()) return pose.front();
    if (it == t_s.end()) return pose.back();
    const std::size_t i = static_cast<std::size_t>(it - t_s.begin());
    const double s = (t - t_s[i - 1]) / (t_s[i] - t_s[i - 1]);
    const Pose2 &a = pose[i - 1], &b = pose[i];
    return {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), normalize_angle(a.theta + s * angle_diff(b.theta, a.theta))};
  }
};

struct CollisionRecord {
  double time_s = 0.0;
  Pose2 pose;
  Eigen::Vector2d point{0, 0};
  std::string obstacle;
};

// What a run leaves behind for the figure and the summary.
struct RunRecord {
  PoseTrack track;
  std::optional<PointCloud> last_sweep;
  std::optional<DepthCloud> last_depth;
  std::vector<CollisionRecord> collisions;  // each time the robot goes from free to touching
  std::uint64_t lidar_sweeps = 0, lidar_points = 0, depth_images = 0, depth_points = 0, odometry_msgs = 0;
  double distance_m = 0.0;
  double wall_s = 0.0;
};

std::size_t finite_points(const PointCloud& c) {
  return static_cast<std::size_t>(
      std::count_if(c.points.begin(), c.points.end(), [](const Eigen::Vector3f& p) { return p.allFinite(); }));
}

void record_frame(const SensorFrame& frame, RunRecord& rec) {
  if (frame.lidar) {
    ++rec.lidar_sweeps;
    rec.lidar_points += frame.lidar->size();
    rec.last_sweep = frame.lidar;
  }
  for (const DepthCloud& d : frame.depth) {
    ++rec.depth_images;
    rec.depth_points += finite_points(d.cloud);
    if (!rec.last_depth || rec.last_depth->camera == d.camera) rec.last_depth = d;  // the first camera's
  }
  rec.odometry_msgs += frame.odometry.has_value();
}

RunRecord run(sim::Simulation& sim, const sim::Scenario& scenario, const RobotProfile& robot,
              const OpenLoopOptions& opt) {
  RunRecord rec;
  const auto steps = static_cast<std::size_t>(std::ceil(opt.duration_s / sim.params().step_s - 1e-9));
  Twist straight;  // without a script: a slow straight line
  straight.linear_x = 0.5 * robot.limits.max_vel_x_mps;
  ProgressBar progress("sim " + scenario.name, steps, opt.progress);
  rec.track.add(sim.now_s(), sim.true_pose());
  bool touching = sim.in_collision();
  const Stopwatch wall;
  for (std::size_t i = 0; i < steps; ++i) {
    const Twist cmd = scenario.commands.empty() ? straight : scenario.command_at(sim.now_s());
    SensorFrame frame = sim.step(cmd);
    rec.distance_m += distance(rec.track.pose.back(), sim.true_pose());
    rec.track.add(sim.now_s(), sim.true_pose());
    record_frame(frame, rec);
    sim.recycle(std::move(frame));  // its clouds' buffers hold the next frames' clouds
    if (sim.in_collision() && !touching)
      rec.collisions.push_back(
          {sim.now_s(), sim.true_pose(), sim.nearest_obstacle().point, sim.nearest_obstacle().obstacle});
    touching = sim.in_collision();
    progress.update(i + 1);
  }
  rec.wall_s = wall.elapsed_ms() / 1000.0;
  progress.finish();
  return rec;
}

// Points of a cloud in the world frame, each from the sensor pose at its own firing time.
std::vector<Eigen::Vector3d> to_world(const PointCloud& cloud, const PoseTrack& track, const SE3& T_base_sensor) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (!cloud.points[i].allFinite()) continue;
    const double t = cloud.stamp_s + (cloud.has_time() ? cloud.time_offsets_s[i] : 0.0);
    out.push_back(se3_from_pose2(track.at(t)) * T_base_sensor * cloud.points[i].cast<double>());
  }
  return out;
}

void draw_cloud(viz::Canvas& canvas, const std::vector<Eigen::Vector3d>& pts, viz::Color above, viz::Color ground) {
  std::vector<Eigen::Vector2d> hi, lo;
  for (const auto& p : pts) (p.z() > 0.05 ? hi : lo).push_back(p.head<2>());
  canvas.points(lo, ground, 1.5);
  canvas.points(hi, above, 2.0);
}

viz::CanvasParams canvas_for(const sim::Bounds& b) {
  viz::CanvasParams cp;
  cp.min_x_m = b.min_x_m, cp.max_x_m = b.max_x_m, cp.min_y_m = b.min_y_m, cp.max_y_m = b.max_y_m;
  cp.pixels_per_m = std::clamp(1200.0 / std::max(b.size_x_m(), b.size_y_m()), 10.0, 200.0);
  cp.margin_px = 30;
  return cp;
}

constexpr viz::Color kLidarColor{0.1, 0.3, 0.95, 0.8}, kDepthColor{0.05, 0.6, 0.2, 0.5};
constexpr viz::Color kDrivenColor{0.0, 0.55, 0.6, 1.0};

// The layers the figure shows (a robot without LiDAR has no sweep to show).
std::vector<viz::LegendEntry> sim_legend(const sim::World& world, const RunRecord& rec) {
  using viz::LegendMark;
  std::vector<viz::LegendEntry> e;
  if (!world.actors.empty()) e.push_back({"moving obstacle", sim::WorldStyle{}.actor_fill, LegendMark::kBox});
  if (rec.last_sweep) e.push_back({"LiDAR points (last sweep)", kLidarColor, LegendMark::kDot});
  if (rec.last_depth) e.push_back({"depth points (last image)", kDepthColor, LegendMark::kDot});
  e.insert(e.end(), {{"driven path", kDrivenColor, LegendMark::kLine},
                     {"start", viz::colors::kGrey, LegendMark::kArrow},
                     {"goal (tolerance)", viz::colors::kRed, LegendMark::kRing},
                     {"robot at the end", viz::colors::kBlack, LegendMark::kArrow}});
  if (!rec.collisions.empty()) e.push_back({"collision", viz::colors::kRed, LegendMark::kCross});
  return e;
}

void draw_collisions(viz::Canvas& canvas, const RunRecord& rec) {
  for (const CollisionRecord& c : rec.collisions) {
    const Eigen::Vector2d q = canvas.to_pixel(c.point);
    canvas.line_px(q - Eigen::Vector2d(6, 6), q + Eigen::Vector2d(6, 6), viz::colors::kRed, 2.5);
    canvas.line_px(q - Eigen::Vector2d(6, -6), q + Eigen::Vector2d(6, -6), viz::colors::kRed, 2.5);
  }
}

// The statics shaded by height (stairs read as steps), the last sweep and depth image, the
// driven path, start, goals, the robot at the end and each collision, with a legend, a scale bar
// and the height ramp.
void write_figure(const fs::path& file, const sim::Simulation& sim, const sim::Scenario& scenario,
                  const RunRecord& rec) {
  const std::vector<viz::LegendEntry> legend = sim_legend(sim.world(), rec);
  viz::Canvas canvas(viz::with_legend_bands(canvas_for(scenario.bounds), legend, viz::kColorRampRoomPx));
  sim::WorldStyle style;
  style.shade_by_height = true;
  sim::draw_world(canvas, sim.world(), sim.now_s(), style);
  const RobotProfile& robot = sim.robot();
  if (rec.last_sweep) {
    const SensorMount* m = robot.sensor(rec.last_sweep->frame_id);
    const SE3 T = m ? m->T_base_sensor() : SE3::Identity();
    draw_cloud(canvas, to_world(*rec.last_sweep, rec.track, T), kLidarColor, {0.55, 0.7, 1.0, 0.4});
  }
  if (rec.last_depth) {
    const SensorMount* m = robot.sensor(rec.last_depth->camera);
    const SE3 T = m ? m->T_base_sensor() : SE3::Identity();
    draw_cloud(canvas, to_world(rec.last_depth->cloud, rec.track, T), kDepthColor, {0.5, 0.85, 0.5, 0.25});
  }
  std::vector<Eigen::Vector2d> path;
  for (const Pose2& p : rec.track.pose) path.push_back(p.position());
  canvas.polyline(path, kDrivenColor, 2.0);
  canvas.arrow(scenario.start, 0.4, viz::colors::kGrey, 2.5);
  const viz::Color goal_colors[] = {viz::colors::kRed, viz::colors::kBlue, viz::colors::kOrange};
  for (std::size_t i = 0; i < scenario.goals.size(); ++i) {
    const viz::Color c = goal_colors[std::min<std::size_t>(i, 2)];
    canvas.circle(scenario.goals[i].pose.position(), scenario.goal_tolerance_m, viz::colors::kNone, c, 2.0);
    canvas.arrow(scenario.goals[i].pose, 0.4, c, 2.0);
  }
  const Pose2 end = sim.true_pose();
  canvas.circle(end.position(), robot.footprint_radius_m, {0.2, 0.2, 0.2, 0.15}, viz::colors::kBlack, 1.5);
  canvas.arrow(end, 0.5, viz::colors::kBlack, 2.5);
  draw_collisions(canvas, rec);
  char title[256];
  std::snprintf(title, sizeof(title), "%s  (%s, t = %.1f s, %zu collision%s)", scenario.name.c_str(),
                robot.name.c_str(), sim.now_s(), rec.collisions.size(), rec.collisions.size() == 1 ? "" : "s");
  const viz::PixelRect rest = viz::draw_title_and_legend(canvas, title, legend);
  char full[32];
  std::snprintf(full, sizeof full, ">= %.1f m", style.full_height_m);
  viz::draw_color_ramp(canvas, rest, style.low_fill, style.static_fill, "0 m", full, "obstacle height (top)");
  canvas.write_png(file);
}

json summary_pose_json(const Pose2& p) { return {{"x_m", p.x}, {"y_m", p.y}, {"theta_rad", p.theta}}; }

json summary(const sim::Simulation& sim, const sim::Scenario& scenario, const RunRecord& rec) {
  json collisions = json::array();
  for (const CollisionRecord& c : rec.collisions)
    collisions.push_back({{"time_s", c.time_s},
                          {"robot", summary_pose_json(c.pose)},
                          {"contact_x_m", c.point.x()},
                          {"contact_y_m", c.point.y()},
                          {"obstacle", c.obstacle}});
  const sim::TimedGoal* goal = scenario.goal_at(sim.now_s());
  return {{"scenario", scenario.name},
          {"world", sim.world().name},
          {"robot", sim.robot().name},
          {"seed", scenario.seed},
          {"duration_s", sim.now_s()},
          {"step_s", sim.params().step_s},
          {"steps", sim.stats().steps},
          {"commands", scenario.commands.empty() ? "straight line" : "scenario script"},
          {"distance_m", rec.distance_m},
          {"start", summary_pose_json(scenario.start)},
          {"final_pose", summary_pose_json(sim.true_pose())},
          {"final_goal_distance_m", goal ? distance(goal->pose, sim.true_pose()) : -1.0},
          {"collision_count", rec.collisions.size()},
          {"collisions", collisions},
          {"min_clearance_m", sim.min_clearance_m()},
          {"lidar_sweeps", rec.lidar_sweeps},
          {"lidar_points", rec.lidar_points},
          {"lidar_points_last_sweep", rec.last_sweep ? rec.last_sweep->size() : 0},
          {"depth_images", rec.depth_images},
          {"depth_points", rec.depth_points},
          {"odometry_messages", rec.odometry_msgs},
          {"lidar_ms", sim.stats().lidar_ms},
          {"depth_ms", sim.stats().depth_ms},
          {"wall_time_s", rec.wall_s},
          {"real_time_factor", rec.wall_s > 0 ? sim.now_s() / rec.wall_s : 0.0}};
}

}  // namespace

json run_open_loop(const sim::Scenario& scenario, const RobotProfile& robot, const sim::SimulationParams& params,
                   const OpenLoopOptions& options, const fs::path& figure_png) {
  sim::Simulation sim(scenario.world, robot, scenario.start, params);
  const RunRecord rec = run(sim, scenario, robot, options);
  write_figure(figure_png, sim, scenario, rec);
  return summary(sim, scenario, rec);
}

}  // namespace bipednav::runner
