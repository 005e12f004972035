#include "bipednav/runner/run_figure.hpp"

#include <cstdio>

#include "bipednav/sim/world_drawing.hpp"
#include "bipednav/viz/canvas.hpp"

namespace bipednav::runner {

namespace {

constexpr viz::Color kWorldFill{0.82, 0.82, 0.82, 1.0};
constexpr viz::Color kTravelled{0.0, 0.55, 0.6, 1.0};
constexpr viz::Color kStart{0.45, 0.45, 0.45, 1.0};
constexpr viz::Color kLocalObstacle = viz::colors::kPurple;
constexpr viz::Color kInflation{0.2, 0.35, 0.95, 0.6};
constexpr double kWindowPadM = 0.5;  // world shown around the scenario's bounds

std::vector<Eigen::Vector2d> positions(const Path& p) {
  std::vector<Eigen::Vector2d> pts;
  for (const auto& q : p.poses) pts.push_back(q.position());
  return pts;
}

void draw_maps(viz::Canvas& c, const Snapshot& snap) {
  viz::CostColors global_palette;
  global_palette.inflated = viz::colors::kNone;
  global_palette.inscribed = viz::colors::kNone;
  global_palette.unknown = viz::colors::kNone;
  c.grid(snap.global_costmap, global_palette);
  viz::CostColors local_palette;
  local_palette.lethal = kLocalObstacle;
  local_palette.unknown = viz::colors::kNone;
  c.grid(snap.local_costmap, local_palette);
}

void draw_markers(viz::Canvas& c, const sim::Scenario& s, double t_s) {
  c.circle(s.start.position(), 0.12, viz::colors::kNone, kStart, 2.0);
  c.arrow(s.start, 0.45, kStart, 2.5);
  const viz::Color goal_colors[2] = {viz::colors::kRed, viz::colors::kBlue};
  for (std::size_t i = 0; i < s.goals.size(); ++i) {
    if (s.goals[i].time_s > t_s) continue;
    const viz::Color col = goal_colors[std::min<std::size_t>(i, 1)];
    c.circle(s.goals[i].pose.position(), std::max(s.goal_tolerance_m, 0.1), viz::colors::kNone, col, 3.0);
    if (s.goals.size() > 1)
      c.text(s.goals[i].pose.position() + Eigen::Vector2d(0.25, 0.25), "goal " + std::to_string(i + 1), col, 13.0);
  }
}

void draw_contacts(viz::Canvas& c, const RunResult& run, double t_s) {
  const std::vector<Eigen::Vector2d> marks = contact_marks(run, t_s);
  for (std::size_t i = 0; i < marks.size(); ++i) {
    const Eigen::Vector2d q = c.to_pixel(marks[i]);
    const double r = i == 0 ? 7.0 : 5.0;
    c.line_px(q - Eigen::Vector2d(r, r), q + Eigen::Vector2d(r, r), viz::colors::kRed, 3.0);
    c.line_px(q - Eigen::Vector2d(r, -r), q + Eigen::Vector2d(r, -r), viz::colors::kRed, 3.0);
  }
}

// One panel: the world and the navigator's state at snap.t_s, drawn into `rect` (clipped to it).
void draw_panel(viz::Canvas& c, const sim::Scenario& s, const RunResult& run, const Snapshot& snap,
                const viz::PixelRect& rect) {
  c.begin_view(rect, s.bounds.min_x_m - kWindowPadM, s.bounds.max_y_m + kWindowPadM);
  c.rect_px(rect, viz::colors::kWhite, viz::colors::kGrey, 1.0);
  sim::WorldStyle style;
  style.static_fill = kWorldFill;
  sim::draw_world(c, s.world, snap.t_s, style);
  draw_maps(c, snap);
  std::vector<Eigen::Vector2d> travelled;
  for (const auto& t : run.trace)
    if (t.t_s <= snap.t_s + 1e-9) travelled.push_back(t.true_pose.position());
  c.polyline(travelled, kTravelled, 2.0);
  c.polyline(positions(snap.global_path), viz::colors::kRed, 2.0);
  c.polyline(positions(snap.local_trajectory), viz::colors::kGreen, 3.0);
  draw_markers(c, s, snap.t_s);
  draw_contacts(c, run, snap.t_s);
  c.arrow(snap.pose, 0.5, viz::colors::kBlack, 3.0);
  c.end_view();
}

void draw_title(viz::Canvas& c, const viz::PixelRect& rect, const std::string& text, double size_px) {
  c.begin_view(rect, 0.0, 0.0);  // clips a long title to its own band
  c.text_px(rect.x + 2, rect.bottom() - 6, text, viz::colors::kBlack, size_px);
  c.end_view();
}

}  // namespace

std::vector<Eigen::Vector2d> contact_marks(const RunResult& run, double t_s) {
  std::vector<Eigen::Vector2d> marks;
  if (run.contacts.empty() && run.first_collision && run.first_collision->time_s <= t_s + 1e-9)
    marks.push_back(run.first_collision->point);
  for (const sim::CollisionEvent& e : run.contacts)
    if (e.time_s <= t_s + 1e-9) marks.push_back(e.point);
  return marks;
}

std::string local_planner_label(const std::string& local_planner) {
  return local_planner == "tracker" ? "path tracker" : local_planner == "teb" ? "TEB" : local_planner;
}

std::vector<viz::LegendEntry> run_figure_legend(const sim::Scenario& s, const RunResult& run,
                                                const std::string& local_planner) {
  using viz::LegendMark;
  std::vector<viz::LegendEntry> e = {{"world (ground truth)", kWorldFill, LegendMark::kBox}};
  if (!s.world.actors.empty()) e.push_back({"moving obstacle", sim::WorldStyle{}.actor_fill, LegendMark::kBox});
  e.insert(e.end(),
           {{"global-map obstacle", viz::colors::kBlack, LegendMark::kBox},
            {"local-map obstacle", kLocalObstacle, LegendMark::kBox},
            {"local-map inflation", kInflation, LegendMark::kBox},
            {"global path", viz::colors::kRed, LegendMark::kLine},
            {"local trajectory (" + local_planner_label(local_planner) + ")", viz::colors::kGreen, LegendMark::kLine},
            {"travelled path (true)", kTravelled, LegendMark::kLine},
            {"start", kStart, LegendMark::kArrow},
            {"goal (tolerance)", viz::colors::kRed, LegendMark::kRing},
            {"robot", viz::colors::kBlack, LegendMark::kArrow}});
  if (run.first_collision || !run.contacts.empty())
    e.push_back({run.collisions > 1 ? "contacts (" + std::to_string(run.collisions) + ")" : "contact",
                 viz::colors::kRed, LegendMark::kCross});
  return e;
}

void write_run_figure(const std::filesystem::path& file, const sim::Scenario& s, const RunResult& run,
                      const std::string& local_planner) {
  const std::vector<viz::LegendEntry> legend = run_figure_legend(s, run, local_planner);
  viz::FigureLayoutParams lp;
  {
    const viz::Canvas scratch(viz::CanvasParams{0, 0, 1, 1, 1});  // measures the legend's text
    const viz::PixelRect box = viz::legend_extent(scratch, legend);
    lp.legend_w_px = std::max(box.w, 130.0);
    lp.legend_h_px = box.h + 60.0;  // and the scale bar under it
  }
  const std::size_t panels = 1 + run.snapshots.size();
  const viz::FigureLayout layout =
      viz::figure_layout(s.bounds.size_x_m() + 2 * kWindowPadM, s.bounds.size_y_m() + 2 * kWindowPadM, panels, lp);
  viz::CanvasParams cp;
  cp.min_x_m = 0.0, cp.min_y_m = 0.0, cp.margin_px = 0;
  cp.pixels_per_m = layout.pixels_per_m;
  cp.max_x_m = layout.width_px / layout.pixels_per_m, cp.max_y_m = layout.height_px / layout.pixels_per_m;
  viz::Canvas canvas(cp);
  char text[200];
  std::snprintf(text, sizeof text, "%s / %s: %s (%s), t = %.1f s, %d collision%s", s.name.c_str(), run.robot.c_str(),
                run.success ? "SUCCESS" : "FAILED", std::string(outcome_name(run.outcome.outcome)).c_str(), run.time_s,
                run.collisions, run.collisions == 1 ? "" : "s");
  draw_title(canvas, layout.header, text, 16.0);
  for (std::size_t i = 0; i < panels; ++i) {
    const Snapshot& snap = i == 0 ? run.final_state : run.snapshots[i - 1];
    std::snprintf(text, sizeof text, i == 0 ? "end of the run, t = %.1f s" : "replanning at t = %.1f s", snap.t_s);
    draw_title(canvas, layout.titles[i], text, 13.0);
    draw_panel(canvas, s, run, snap, layout.panels[i]);
  }
  const viz::PixelRect box = viz::draw_legend(canvas, layout.legend.x, layout.legend.y, legend);
  viz::draw_scale_bar(canvas, layout.legend.x + 6, box.bottom() + 16, layout.legend.w - 12);
  canvas.write_png(file);
}

}  // namespace bipednav::runner
