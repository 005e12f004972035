#include "bipednav/planning/footstep/inverse_heightmap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bipednav::planning::footstep {

namespace {

struct PlanarPose {
  double x, y, heading;
};

PlanarPose lerp(const PlanarPose& a, const PlanarPose& b, double s) {
  return {a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), a.heading + s * (b.heading - a.heading)};
}

bool inside(const Rect& r, double px, double py) {
  const double c = std::cos(r.heading), s = std::sin(r.heading);
  const double dx = px - r.cx, dy = py - r.cy;
  return std::abs(c * dx + s * dy) <= r.half_x && std::abs(-s * dx + c * dy) <= r.half_y;
}

// Accumulates the per-cell minimum height of body parts on a dense square around the stance.
class SweptVolume {
 public:
  SweptVolume(double theta, double res, double half_extent_m, std::vector<Rect> soles)
      : theta_(theta),
        res_(res),
        half_(static_cast<int>(std::ceil(half_extent_m / res))),
        side_(2 * half_ + 1),
        height_(static_cast<std::size_t>(side_) * side_, std::numeric_limits<float>::infinity()),
        soles_(std::move(soles)),
        ct_(std::cos(theta)),
        st_(std::sin(theta)) {}

  void add(const Rect& r, double bottom_m, bool skip_soles) {
    const float b = static_cast<float>(bottom_m);
    rasterize_rect(r, theta_, res_, res_ / 2.0, [&](int x, int y) {
      if (std::abs(x) > half_ || std::abs(y) > half_) return;
      float& h = height_[static_cast<std::size_t>(y + half_) * side_ + (x + half_)];
      if (b >= h || (skip_soles && on_sole(x, y))) return;
      h = b;
    });
  }
  // Bands: below 0.1 m (soles in the air), below the torso (legs), the rest (body).
  InverseHeightmap result(double torso_bottom_m) const {
    const float bounds[3] = {0.1f, static_cast<float>(torso_bottom_m) - 1e-4f, std::numeric_limits<float>::infinity()};
    InverseHeightmap out;
    out.layers.resize(3);
    for (auto& l : out.layers) {
      l.min_height_m = std::numeric_limits<float>::infinity();
      l.min_dx = l.min_dy = half_;
      l.max_dx = l.max_dy = -half_;
    }
    for (int y = -half_; y <= half_; ++y) {
      for (int x = -half_; x <= half_; ++x) {
        const float h = height_[static_cast<std::size_t>(y + half_) * side_ + (x + half_)];
        if (!std::isfinite(h)) continue;
        IhmLayer& l = out.layers[h < bounds[0] ? 0 : (h < bounds[1] ? 1 : 2)];
        l.cells.push_back({static_cast<std::int16_t>(x), static_cast<std::int16_t>(y), h});
        l.min_dx = std::min(l.min_dx, x);
        l.max_dx = std::max(l.max_dx, x);
        l.min_dy = std::min(l.min_dy, y);
        l.max_dy = std::max(l.max_dy, y);
        l.min_height_m = std::min(l.min_height_m, h);
      }
    }
    std::erase_if(out.layers, [](const IhmLayer& l) { return l.cells.empty(); });
    return out;
  }

 private:
  bool on_sole(int x, int y) const {
    // Lattice cell centre back into the stance frame.
    const double px = ct_ * x * res_ + st_ * y * res_, py = -st_ * x * res_ + ct_ * y * res_;
    return std::any_of(soles_.begin(), soles_.end(), [&](const Rect& r) { return inside(r, px, py); });
  }

  double theta_, res_;
  int half_, side_;
  std::vector<float> height_;
  std::vector<Rect> soles_;
  double ct_, st_;
};

Rect sole(const BodyModel& b, const PlanarPose& p) {
  return {p.x, p.y, p.heading, b.foot_length_m / 2.0, b.foot_width_m / 2.0};
}

void add_body(SweptVolume& vol, const BodyModel& b, const PlanarPose& left, const PlanarPose& right) {
  const PlanarPose c{(left.x + right.x) / 2, (left.y + right.y) / 2, (left.heading + right.heading) / 2};
  const double cs = std::cos(c.heading), sn = std::sin(c.heading);
  vol.add({c.x, c.y, c.heading, b.torso_depth_m / 2, b.torso_width_m / 2}, b.torso_bottom_m, false);
  for (double side : {-1.0, 1.0}) {
    const double ox = -sn * side * b.arm_offset_m, oy = cs * side * b.arm_offset_m;
    vol.add({c.x + ox, c.y + oy, c.heading, b.arm_depth_m / 2, b.arm_width_m / 2}, b.arm_bottom_m, false);
  }
}

void add_swing(SweptVolume& vol, const BodyModel& b, const PlanarPose& foot, double peak) {
  vol.add(sole(b, foot), peak, true);
  vol.add({foot.x, foot.y, foot.heading, b.leg_width_m / 2, b.leg_width_m / 2}, peak + b.ankle_height_m, true);
}

}  // namespace

InverseHeightmap build_inverse_heightmap(const FootstepAction& a, const BodyModel& b, Foot stance, double theta,
                                         double res, double swing_lift_m, bool stance_landed) {
  const double m = stance == Foot::kLeft ? 1.0 : -1.0;  // mirror for a right stance foot
  const double sep = b.nominal_separation_m;
  const PlanarPose stance_pose{0, 0, 0};
  const PlanarPose via0{0, -m * sep, 0};
  const PlanarPose land{a.dx_m, m * a.dy_m, m * a.dtheta_rad};
  const PlanarPose via1{land.x - std::sin(land.heading) * m * sep, land.y + std::cos(land.heading) * m * sep,
                        land.heading};
  const double reach = std::hypot(a.dx_m, a.dy_m) + 2.0 * sep + b.arm_offset_m + b.foot_length_m + b.arm_depth_m;
  SweptVolume vol(theta, res, reach, {sole(b, stance_pose), sole(b, land)});
  constexpr int kSamples = 12;
  for (int k = 0; k <= kSamples; ++k) {
    const double s = static_cast<double>(k) / kSamples;
    // Downward phase: swing foot from its via point to the landing pose (section V-C).
    const PlanarPose swing = lerp(via0, land, s);
    add_swing(vol, b, swing, a.peak_m + swing_lift_m);
    add_body(vol, b, stance_pose, swing);
    // Upward phase: the old stance foot rises to the via point beside the new stance foot.
    const PlanarPose trail = lerp(stance_pose, via1, s);
    if (k > 0 || !stance_landed) add_swing(vol, b, trail, a.peak_m);
    add_body(vol, b, trail, land);
  }
  return vol.result(b.torso_bottom_m);
}

std::vector<std::pair<std::int16_t, std::int16_t>> footprint_cells(const BodyModel& b, double theta, double res,
                                                                   double grow_m) {
  std::vector<std::pair<std::int16_t, std::int16_t>> out;
  rasterize_rect(sole(b, {0, 0, 0}), theta, res, grow_m,
                 [&](int x, int y) { out.emplace_back(static_cast<std::int16_t>(x), static_cast<std::int16_t>(y)); });
  if (out.empty()) out.emplace_back(0, 0);
  return out;
}

}  // namespace bipednav::planning::footstep
