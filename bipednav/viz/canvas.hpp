#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "bipednav/common/pose2.hpp"
#include "bipednav/mapping/costmap2d.hpp"

typedef struct _cairo cairo_t;
typedef struct _cairo_surface cairo_surface_t;

namespace bipednav::viz {

struct Color {
  double r = 0.0, g = 0.0, b = 0.0, a = 1.0;
};

namespace colors {
inline constexpr Color kWhite{1, 1, 1, 1};
inline constexpr Color kBlack{0, 0, 0, 1};
inline constexpr Color kGrey{0.55, 0.55, 0.55, 1};
inline constexpr Color kLightGrey{0.85, 0.85, 0.85, 1};
inline constexpr Color kRed{0.85, 0.1, 0.1, 1};
inline constexpr Color kGreen{0.1, 0.65, 0.2, 1};
inline constexpr Color kBlue{0.15, 0.3, 0.9, 1};
inline constexpr Color kPurple{0.55, 0.15, 0.65, 1};
inline constexpr Color kOrange{0.95, 0.55, 0.1, 1};
inline constexpr Color kNone{0, 0, 0, 0};
}  // namespace colors

// Colours of the cost classes of a Costmap2D (ROS convention, mapping/costmap2d.hpp), as in the
// reference's figures: lethal black (global map) or purple (local map), inflation blue.
struct CostColors {
  Color free = colors::kNone;                // cost 0
  Color inflated = {0.2, 0.35, 0.95, 0.45};  // 1..252, alpha grows with the cost
  Color inscribed = {0.2, 0.35, 0.95, 0.8};  // 253
  Color lethal = colors::kBlack;             // 254
  Color unknown = {0.5, 0.5, 0.5, 0.25};     // 255
};

// The visible window of the world and the resolution of the picture.
struct CanvasParams {
  double min_x_m = -5.0, min_y_m = -5.0, max_x_m = 5.0, max_y_m = 5.0;
  double pixels_per_m = 50.0;
  int margin_px = 20;
  Color background = colors::kWhite;
  // Bands outside the world's window: a title above it, a legend right of it, room below it.
  int top_px = 0, right_px = 0, bottom_px = 0;

  void validate() const;
};

// A rectangle of the picture in pixels, (0, 0) the top-left corner.
struct PixelRect {
  double x = 0.0, y = 0.0, w = 0.0, h = 0.0;
  double right() const { return x + w; }
  double bottom() const { return y + h; }
};

// A top-view drawing in world coordinates (metres, y up, x right). Everything is recorded and
// rendered when written, to PNG. Line widths and text sizes are in pixels.
class Canvas {
 public:
  explicit Canvas(const CanvasParams& params);
  ~Canvas();
  Canvas(const Canvas&) = delete;
  Canvas& operator=(const Canvas&) = delete;

  int width_px() const { return width_px_; }
  int height_px() const { return height_px_; }
  const CanvasParams& params() const { return params_; }
  Eigen::Vector2d to_pixel(const Eigen::Vector2d& world) const;
  // The world's window in the picture (without the margin and the bands).
  PixelRect world_rect() const;

  // Draws the world into `rect` (a figure panel) until end_view(): the point (min_x_m, max_y_m) at
  // the rectangle's top-left corner, at the canvas' scale, everything clipped to the rectangle.
  void begin_view(const PixelRect& rect, double min_x_m, double max_y_m);
  void end_view();

  void polygon(const std::vector<Eigen::Vector2d>& pts, Color fill, Color stroke = colors::kNone,
               double width_px = 1.0);
  void polyline(const std::vector<Eigen::Vector2d>& pts, Color stroke, double width_px = 1.0);
  void line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, Color stroke, double width_px = 1.0);
  void circle(const Eigen::Vector2d& centre, double radius_m, Color fill, Color stroke = colors::kNone,
              double width_px = 1.0);
  // Points as small squares of `size_px` (fast for clouds of 10^5 points).
  void points(const std::vector<Eigen::Vector2d>& pts, Color fill, double size_px = 2.0);
  // An arrow from the pose's position along its heading.
  void arrow(const Pose2& pose, double length_m, Color stroke, double width_px = 2.0);
  void text(const Eigen::Vector2d& world, const std::string& s, Color color, double size_px = 12.0);
  // Text at a pixel position (titles, legends); (0, 0) is the top-left corner; y is the baseline.
  void text_px(double x_px, double y_px, const std::string& s, Color color, double size_px = 12.0);
  // The width of a text in pixels.
  double text_width_px(const std::string& s, double size_px = 12.0) const;
  // Pixel-positioned shapes (legends, scale bars).
  void rect_px(const PixelRect& r, Color fill, Color stroke = colors::kNone, double width_px = 1.0);
  void line_px(const Eigen::Vector2d& a_px, const Eigen::Vector2d& b_px, Color stroke, double width_px = 1.0);
  void circle_px(const Eigen::Vector2d& centre_px, double radius_px, Color fill, Color stroke = colors::kNone,
                 double width_px = 1.0);
  // Every cell of the grid in its cost class colour (one image, nearest-neighbour scaled).
  void grid(const mapping::Costmap2D& costmap, const CostColors& palette = {});

  // Throws FileError when the file cannot be written.
  void write_png(const std::filesystem::path& file) const;

 private:
  void set_color(Color c);
  void fill_and_stroke(Color fill, Color stroke, double width_px);

  CanvasParams params_;
  // The current view: where (view_min_x_m_, view_max_y_m_) is drawn.
  Eigen::Vector2d view_origin_px_{0, 0};
  double view_min_x_m_ = 0.0, view_max_y_m_ = 0.0;
  bool in_view_ = false;
  int width_px_ = 0;
  int height_px_ = 0;
  cairo_surface_t* recording_ = nullptr;
  cairo_t* cr_ = nullptr;
};

// The colour of one cost value under a palette (used by grid()).
Color cost_color(std::uint8_t cost, const CostColors& palette);

}  // namespace bipednav::viz
