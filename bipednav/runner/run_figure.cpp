#include "bipednav/runner/run_figure.hpp"

#include <cstdio>

#include "bipednav/sim/world_drawing.hpp"
#include "bipednav/viz/canvas.hpp"

namespace bipednav::runner {

namespace {

struct Panel {
  Eigen::Vector2d offset;  // added to world coordinates
};

std::vector<Eigen::Vector2d> shifted(const Path& p, const Eigen::Vector2d& off) {
  std::vector<Eigen::Vector2d> pts;
  for (const auto& q : p.poses) pts.push_back(q.position() + off);
  return pts;
}

// Draws a costmap shifted by `off` (the canvas draws grids at their own geometry).
void draw_grid(viz::Canvas& c, mapping::Costmap2D map, const Eigen::Vector2d& off, const viz::CostColors& palette) {
  mapping::GridGeometry g = map.geometry();
  g.origin_x_m += off.x();
  g.origin_y_m += off.y();
  mapping::Costmap2D moved(g);
  moved.data() = map.data();
  c.grid(moved, palette);
}

void draw_panel(viz::Canvas& c, const sim::Scenario& s, const Snapshot& snap, const std::vector<TraceSample>& trace,
                const Eigen::Vector2d& off, const std::string& title) {
  sim::World world = s.world;
  for (auto& geom : world.statics) geom.T_parent_shape.pretranslate(Eigen::Vector3d(off.x(), off.y(), 0.0));
  for (auto& a : world.actors)
    for (auto& w : a.trajectory) w.pose.pretranslate(Eigen::Vector3d(off.x(), off.y(), 0.0));
  sim::WorldStyle style;
  style.static_fill = {0.8, 0.8, 0.8, 1.0};
  sim::draw_world(c, world, snap.t_s, style);
  viz::CostColors global_palette;
  global_palette.inflated = viz::colors::kNone;
  global_palette.inscribed = viz::colors::kNone;
  draw_grid(c, snap.global_costmap, off, global_palette);
  viz::CostColors local_palette;
  local_palette.lethal = viz::colors::kPurple;
  local_palette.unknown = viz::colors::kNone;
  draw_grid(c, snap.local_costmap, off, local_palette);
  std::vector<Eigen::Vector2d> travelled;
  for (const auto& t : trace)
    if (t.t_s <= snap.t_s + 1e-9) travelled.push_back(t.true_pose.position() + off);
  c.polyline(travelled, viz::colors::kPurple, 2.0);
  c.polyline(shifted(snap.global_path, off), viz::colors::kRed, 2.0);
  c.polyline(shifted(snap.local_trajectory, off), viz::colors::kGreen, 3.0);
  const viz::Color goal_colors[2] = {viz::colors::kRed, viz::colors::kBlue};
  for (std::size_t i = 0; i < s.goals.size(); ++i) {
    if (s.goals[i].time_s > snap.t_s) continue;
    c.circle(s.goals[i].pose.position() + off, 0.2, viz::colors::kNone, goal_colors[std::min<std::size_t>(i, 1)], 3.0);
  }
  Pose2 robot = snap.pose;
  robot.x += off.x();
  robot.y += off.y();
  c.arrow(robot, 0.5, viz::colors::kRed, 3.0);
  const double top = s.bounds.max_y_m + off.y() + 0.6;
  c.text({s.bounds.min_x_m + off.x(), top}, title, viz::colors::kBlack, 16.0);
}

}  // namespace

void write_run_figure(const std::filesystem::path& file, const sim::Scenario& s, const RunResult& run) {
  const double w = s.bounds.size_x_m() + 1.5, h = s.bounds.size_y_m() + 2.0;
  const bool in_row = w <= h * 1.5;  // wide worlds stack their panels vertically
  const std::size_t panels = 1 + run.snapshots.size();
  viz::CanvasParams cp;
  cp.min_x_m = s.bounds.min_x_m - 0.5;
  cp.min_y_m = s.bounds.min_y_m - 0.5 - (in_row ? 0.0 : h * (panels - 1));
  cp.max_x_m = s.bounds.max_x_m + 0.5 + (in_row ? w * (panels - 1) : 0.0);
  cp.max_y_m = s.bounds.max_y_m + 1.2;
  cp.pixels_per_m = std::clamp(900.0 / std::max(w, h), 20.0, 120.0);
  viz::Canvas canvas(cp);
  char title[160];
  std::snprintf(title, sizeof(title), "%s / %s: %s (%s) t=%.1f s", s.name.c_str(), run.robot.c_str(),
                run.success ? "SUCCESS" : "FAILED", std::string(outcome_name(run.outcome.outcome)).c_str(), run.time_s);
  draw_panel(canvas, s, run.final_state, run.trace, {0, 0}, title);
  for (std::size_t i = 0; i < run.snapshots.size(); ++i) {
    const Eigen::Vector2d off = in_row ? Eigen::Vector2d(w * (i + 1), 0) : Eigen::Vector2d(0, -h * (i + 1));
    std::snprintf(title, sizeof(title), "replanning at t=%.1f s", run.snapshots[i].t_s);
    draw_panel(canvas, s, run.snapshots[i], run.trace, off, title);
  }
  canvas.write_png(file);
}

}  // namespace bipednav::runner
