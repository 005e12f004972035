#include "bipednav/runner/footstep_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bipednav/mapping/costmap2d.hpp"
#include "bipednav/viz/figure_legend.hpp"

namespace bipednav::runner {

viz::CanvasParams canvas_for(const mapping::GridGeometry& g) {
  return {g.origin_x_m, g.origin_y_m, g.origin_x_m + g.size_x_m(), g.origin_y_m + g.size_y_m(),
          std::clamp(800.0 / std::max(g.size_x_m(), g.size_y_m()), 20.0, 400.0)};
}

HeightRange draw_heightmap(viz::Canvas& c, const mapping::Heightmap& map) {
  const auto& g = map.geometry();
  float lo = 1e9f, hi = -1e9f;
  for (float h : map.heights())
    if (std::isfinite(h)) lo = std::min(lo, h), hi = std::max(hi, h);
  mapping::Costmap2D shade(g, mapping::kUnknown);
  for (std::size_t i = 0; i < g.size(); ++i) {
    const float h = map.heights()[i];
    if (std::isfinite(h)) shade.data()[i] = hi > lo ? static_cast<std::uint8_t>(1 + 250.0 * (h - lo) / (hi - lo)) : 1;
  }
  viz::CostColors grey;
  grey.inflated = {0.0, 0.0, 0.0, 0.9};
  grey.unknown = {0.9, 0.7, 0.7, 1.0};
  c.grid(shade, grey);
  return hi >= lo ? HeightRange{lo, hi} : HeightRange{};
}

void draw_footsteps(viz::Canvas& c, const planning::footstep::BodyModel& body,
                    const std::vector<planning::footstep::Footstep>& steps, const std::vector<std::string>& actions,
                    double fill_alpha, double line_px) {
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const planning::footstep::Footstep& f = steps[i];
    std::vector<Eigen::Vector2d> corners;
    for (auto [sx, sy] : {std::pair{1, 1}, {-1, 1}, {-1, -1}, {1, -1}})
      corners.push_back(f.pose.transform({sx * body.foot_length_m / 2, sy * body.foot_width_m / 2}));
    const std::string* action = i > 0 && i - 1 < actions.size() ? &actions[i - 1] : nullptr;
    const bool special = action && (action->rfind("step_", 0) == 0 || *action == "t_step");
    const viz::Color col = f.foot == planning::footstep::Foot::kLeft ? viz::colors::kBlue : viz::colors::kRed;
    c.polygon(corners, {col.r, col.g, col.b, fill_alpha}, special ? viz::colors::kOrange : col,
              special ? 2.0 * line_px : line_px);
  }
}

void draw_goal(viz::Canvas& c, const Pose2& goal) {
  c.circle(goal.position(), 0.05, viz::colors::kNone, viz::colors::kGreen, 3.0);
  c.arrow(goal, 0.15, viz::colors::kGreen, 2.0);
}

void draw_start(viz::Canvas& c, const Pose2& start) {
  c.circle(start.position(), 0.05, viz::colors::kNone, viz::colors::kGrey, 3.0);
  c.arrow(start, 0.15, viz::colors::kGrey, 2.0);
}

namespace {

std::vector<viz::LegendEntry> footstep_legend(bool with_path) {
  using viz::LegendMark;
  std::vector<viz::LegendEntry> e = {
      {"left foot", viz::colors::kBlue, LegendMark::kBox, {0.15, 0.3, 0.9, 0.35}},
      {"right foot", viz::colors::kRed, LegendMark::kBox, {0.85, 0.1, 0.1, 0.35}},
      {"3D step (over / onto / down)", viz::colors::kOrange, LegendMark::kBox, viz::colors::kWhite},
      {"start", viz::colors::kGrey, LegendMark::kArrow},
      {"goal", viz::colors::kGreen, LegendMark::kArrow},
      {"unobserved", {0.9, 0.7, 0.7, 1.0}, LegendMark::kBox}};
  if (with_path) {
    e.push_back({"last plan (faint)", {0.15, 0.3, 0.9, 0.5}, LegendMark::kBox, {0.15, 0.3, 0.9, 0.08}});
    e.push_back({"body path", viz::colors::kPurple, LegendMark::kLine});
    e.push_back({"robot at the end", viz::colors::kBlack, LegendMark::kArrow});
    e.push_back({"contact", viz::colors::kRed, LegendMark::kRing});
  }
  return e;
}

}  // namespace

viz::CanvasParams footstep_canvas(const mapping::GridGeometry& g, bool with_path) {
  return viz::with_legend_bands(canvas_for(g), footstep_legend(with_path), viz::kColorRampRoomPx);
}

void draw_footstep_legend(viz::Canvas& c, const std::string& title, const HeightRange& heights, bool with_path) {
  const viz::PixelRect rest = viz::draw_title_and_legend(c, title, footstep_legend(with_path));
  char lo[32], hi[32];
  const auto no_negative_zero = [](double v) { return std::abs(v) < 0.005 ? 0.0 : v; };
  std::snprintf(lo, sizeof lo, "%.2f m", no_negative_zero(heights.lo_m));
  std::snprintf(hi, sizeof hi, "%.2f m", no_negative_zero(heights.hi_m));
  viz::draw_color_ramp(c, rest, {0, 0, 0, 0.27}, {0, 0, 0, 0.9}, lo, hi, "height");
}

}  // namespace bipednav::runner
