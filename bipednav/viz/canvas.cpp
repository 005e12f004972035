#include "bipednav/viz/canvas.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::viz {

void CanvasParams::validate() const {
  require(std::isfinite(min_x_m) && std::isfinite(max_x_m) && max_x_m > min_x_m, "max_x_m", "> min_x_m, finite");
  require(std::isfinite(min_y_m) && std::isfinite(max_y_m) && max_y_m > min_y_m, "max_y_m", "> min_y_m, finite");
  require(pixels_per_m > 0.0, "pixels_per_m", "> 0");
  require(margin_px >= 0, "margin_px", ">= 0");
  const auto band = [](int px) { return px >= 0 && px <= 20000; };
  require(band(top_px) && band(right_px) && band(bottom_px), "top_px",
          "bands of 0..20000 pixels (and right_px, bottom_px)");
  const double w = (max_x_m - min_x_m) * pixels_per_m, h = (max_y_m - min_y_m) * pixels_per_m;
  require(w <= 20000 && h <= 20000, "pixels_per_m", "a picture of at most 20000 x 20000 pixels");
}

Canvas::Canvas(const CanvasParams& params) : params_(params) {
  params_.validate();
  width_px_ = static_cast<int>(std::ceil((params_.max_x_m - params_.min_x_m) * params_.pixels_per_m)) +
              2 * params_.margin_px + params_.right_px;
  height_px_ = static_cast<int>(std::ceil((params_.max_y_m - params_.min_y_m) * params_.pixels_per_m)) +
               2 * params_.margin_px + params_.top_px + params_.bottom_px;
  end_view();
  const cairo_rectangle_t extents{0, 0, static_cast<double>(width_px_), static_cast<double>(height_px_)};
  recording_ = cairo_recording_surface_create(CAIRO_CONTENT_COLOR_ALPHA, &extents);
  cr_ = cairo_create(recording_);
  set_color(params_.background);
  cairo_paint(cr_);
  cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr_, CAIRO_LINE_CAP_ROUND);
}

Canvas::~Canvas() {
  cairo_destroy(cr_);
  cairo_surface_destroy(recording_);
}

Eigen::Vector2d Canvas::to_pixel(const Eigen::Vector2d& w) const {
  return {view_origin_px_.x() + (w.x() - view_min_x_m_) * params_.pixels_per_m,
          view_origin_px_.y() + (view_max_y_m_ - w.y()) * params_.pixels_per_m};
}

PixelRect Canvas::world_rect() const {
  const double m = params_.margin_px;
  return {m, m + params_.top_px, (params_.max_x_m - params_.min_x_m) * params_.pixels_per_m,
          (params_.max_y_m - params_.min_y_m) * params_.pixels_per_m};
}

void Canvas::begin_view(const PixelRect& rect, double min_x_m, double max_y_m) {
  if (in_view_) end_view();
  view_origin_px_ = {rect.x, rect.y};
  view_min_x_m_ = min_x_m;
  view_max_y_m_ = max_y_m;
  cairo_save(cr_);
  cairo_rectangle(cr_, rect.x, rect.y, rect.w, rect.h);
  cairo_clip(cr_);
  in_view_ = true;
}

void Canvas::end_view() {
  if (in_view_) cairo_restore(cr_);
  in_view_ = false;
  const PixelRect r = world_rect();
  view_origin_px_ = {r.x, r.y};
  view_min_x_m_ = params_.min_x_m;
  view_max_y_m_ = params_.max_y_m;
}

void Canvas::set_color(Color c) { cairo_set_source_rgba(cr_, c.r, c.g, c.b, c.a); }

void Canvas::fill_and_stroke(Color fill, Color stroke, double width_px) {
  if (fill.a > 0) {
    set_color(fill);
    stroke.a > 0 ? cairo_fill_preserve(cr_) : cairo_fill(cr_);
  }
  if (stroke.a > 0) {
    set_color(stroke);
    cairo_set_line_width(cr_, width_px);
    cairo_stroke(cr_);
  }
  cairo_new_path(cr_);
}

void Canvas::polygon(const std::vector<Eigen::Vector2d>& pts, Color fill, Color stroke, double width_px) {
  if (pts.size() < 2) return;
  for (const auto& p : pts) {
    const Eigen::Vector2d q = to_pixel(p);
    cairo_line_to(cr_, q.x(), q.y());
  }
  cairo_close_path(cr_);
  fill_and_stroke(fill, stroke, width_px);
}

void Canvas::polyline(const std::vector<Eigen::Vector2d>& pts, Color stroke, double width_px) {
  if (pts.size() < 2) return;
  for (const auto& p : pts) {
    const Eigen::Vector2d q = to_pixel(p);
    cairo_line_to(cr_, q.x(), q.y());
  }
  fill_and_stroke(colors::kNone, stroke, width_px);
}

void Canvas::line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Color stroke, double width_px) {
  polyline({a, b}, stroke, width_px);
}

void Canvas::circle(const Eigen::Vector2d& centre, double radius_m, Color fill, Color stroke, double width_px) {
  circle_px(to_pixel(centre), radius_m * params_.pixels_per_m, fill, stroke, width_px);
}

void Canvas::points(const std::vector<Eigen::Vector2d>& pts, Color fill, double size_px) {
  if (pts.empty()) return;
  for (const auto& p : pts) {
    if (!p.allFinite()) continue;
    const Eigen::Vector2d q = to_pixel(p);
    cairo_rectangle(cr_, q.x() - 0.5 * size_px, q.y() - 0.5 * size_px, size_px, size_px);
  }
  fill_and_stroke(fill, colors::kNone, 0.0);
}

void Canvas::arrow(const Pose2& pose, double length_m, Color stroke, double width_px) {
  const Eigen::Vector2d a = pose.position();
  const Eigen::Vector2d dir(std::cos(pose.theta), std::sin(pose.theta));
  const Eigen::Vector2d b = a + length_m * dir;
  line(a, b, stroke, width_px);
  const double head = 0.3 * length_m;
  const Eigen::Vector2d left(-dir.y(), dir.x());
  polygon({b, b - head * dir + 0.5 * head * left, b - head * dir - 0.5 * head * left}, stroke);
}

void Canvas::text(const Eigen::Vector2d& world, const std::string& s, Color color, double size_px) {
  const Eigen::Vector2d q = to_pixel(world);
  text_px(q.x(), q.y(), s, color, size_px);
}

void Canvas::text_px(double x_px, double y_px, const std::string& s, Color color, double size_px) {
  cairo_select_font_face(cr_, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr_, size_px);
  set_color(color);
  cairo_move_to(cr_, x_px, y_px);
  cairo_show_text(cr_, s.c_str());
  cairo_new_path(cr_);
}

double Canvas::text_width_px(const std::string& s, double size_px) const {
  cairo_save(cr_);
  cairo_select_font_face(cr_, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr_, size_px);
  cairo_text_extents_t e;
  cairo_text_extents(cr_, s.c_str(), &e);
  cairo_restore(cr_);
  return e.x_advance;
}

void Canvas::rect_px(const PixelRect& r, Color fill, Color stroke, double width_px) {
  cairo_rectangle(cr_, r.x, r.y, r.w, r.h);
  fill_and_stroke(fill, stroke, width_px);
}

void Canvas::line_px(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Color stroke, double width_px) {
  cairo_move_to(cr_, a.x(), a.y());
  cairo_line_to(cr_, b.x(), b.y());
  fill_and_stroke(colors::kNone, stroke, width_px);
}

void Canvas::circle_px(const Eigen::Vector2d& q, double radius_px, Color fill, Color stroke, double width_px) {
  cairo_new_sub_path(cr_);
  cairo_arc(cr_, q.x(), q.y(), radius_px, 0.0, 2.0 * M_PI);
  fill_and_stroke(fill, stroke, width_px);
}

Color cost_color(std::uint8_t cost, const CostColors& palette) {
  if (cost == mapping::kFree) return palette.free;
  if (cost == mapping::kLethal) return palette.lethal;
  if (cost == mapping::kInscribed) return palette.inscribed;
  if (cost == mapping::kUnknown) return palette.unknown;
  Color c = palette.inflated;
  c.a *= 0.3 + 0.7 * static_cast<double>(cost) / static_cast<double>(mapping::kInscribed);
  return c;
}

void Canvas::grid(const mapping::Costmap2D& costmap, const CostColors& palette) {
  const int w = costmap.width(), h = costmap.height();
  if (w <= 0 || h <= 0) return;
  cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
  cairo_surface_flush(img);
  unsigned char* data = cairo_image_surface_get_data(img);
  const int stride = cairo_image_surface_get_stride(img);
  for (int y = 0; y < h; ++y) {
    // Image rows go down, grid rows go up (y up).
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::ptrdiff_t>(h - 1 - y) * stride);
    for (int x = 0; x < w; ++x) {
      const Color c = cost_color(costmap.cost(x, y), palette);
      const auto ch = [&](double v) {
        return static_cast<std::uint32_t>(std::lround(std::clamp(v * c.a, 0.0, 1.0) * 255));
      };
      // Premultiplied ARGB32 in native endianness.
      row[x] = (ch(1.0) << 24) | (ch(c.r) << 16) | (ch(c.g) << 8) | ch(c.b);
    }
  }
  cairo_surface_mark_dirty(img);
  const auto& g = costmap.geometry();
  const Eigen::Vector2d top_left = to_pixel({g.origin_x_m, g.origin_y_m + g.size_y_m()});
  const double scale = g.resolution_m * params_.pixels_per_m;
  cairo_save(cr_);
  cairo_translate(cr_, top_left.x(), top_left.y());
  cairo_scale(cr_, scale, scale);
  cairo_set_source_surface(cr_, img, 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr_), CAIRO_FILTER_NEAREST);
  cairo_rectangle(cr_, 0, 0, w, h);
  cairo_fill(cr_);
  cairo_restore(cr_);
  cairo_surface_destroy(img);
}

namespace {

// Replays the recording onto `target` and reports cairo's status.
cairo_status_t replay(cairo_surface_t* recording, cairo_surface_t* target) {
  cairo_t* cr = cairo_create(target);
  cairo_set_source_surface(cr, recording, 0, 0);
  cairo_paint(cr);
  const cairo_status_t st = cairo_status(cr);
  cairo_destroy(cr);
  return st;
}

}  // namespace

void Canvas::write_png(const std::filesystem::path& file) const {
  cairo_surface_flush(recording_);
  cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width_px_, height_px_);
  cairo_status_t st = replay(recording_, img);
  if (st == CAIRO_STATUS_SUCCESS) st = cairo_surface_write_to_png(img, file.string().c_str());
  cairo_surface_destroy(img);
  if (st != CAIRO_STATUS_SUCCESS)
    throw FileError(file.string(), "", std::string("cannot write PNG: ") + cairo_status_to_string(st));
}

}  // namespace bipednav::viz
