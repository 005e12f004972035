#include "bipednav/sim/humanoid_walker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bipednav/common/error.hpp"
#include "bipednav/mapping/heightmap_fusion.hpp"

namespace bipednav::sim {

void HumanoidWalkerParams::validate() const {
  body.validate();
  require(landing_noise_xy_m >= 0.0 && landing_noise_yaw_rad >= 0.0, "landing_noise_xy_m/yaw_rad", ">= 0");
  require(odometry_noise_xy_m >= 0.0 && odometry_noise_yaw_rad >= 0.0, "odometry_noise_xy_m/yaw_rad", ">= 0");
  require(collision_tolerance_m >= 0.0, "collision_tolerance_m", ">= 0");
  require(min_support_ratio >= 0.0 && min_support_ratio <= 1.0, "min_support_ratio", "in [0, 1]");
  require(support_band_m >= 0.0, "support_band_m", ">= 0");
  require(sole_edge_tolerance_m >= 0.0, "sole_edge_tolerance_m", ">= 0");
  require(samples_per_segment >= 1, "samples_per_segment", ">= 1");
}

Pose2 body_between(const Pose2& a, const Pose2& b) {
  return {(a.x + b.x) / 2.0, (a.y + b.y) / 2.0, normalize_angle(a.theta + angle_diff(b.theta, a.theta) / 2.0)};
}

std::vector<BodyPart> upper_body_parts(const BodyModel& body, const Pose2& a, const Pose2& b, double support_z_m) {
  const Pose2 c = body_between(a, b);
  std::vector<BodyPart> parts;
  parts.push_back({"torso", c, body.torso_depth_m, body.torso_width_m, support_z_m + body.torso_bottom_m});
  parts.push_back({"left_arm", c * Pose2{0.0, body.arm_offset_m, 0.0}, body.arm_depth_m, body.arm_width_m,
                   support_z_m + body.arm_bottom_m});
  parts.push_back({"right_arm", c * Pose2{0.0, -body.arm_offset_m, 0.0}, body.arm_depth_m, body.arm_width_m,
                   support_z_m + body.arm_bottom_m});
  return parts;
}

double part_clearance_m(const mapping::Heightmap& truth, const BodyPart& part) {
  const auto h = mapping::footprint_heights(truth, part.pose, part.length_m, part.width_m);
  if (h.known_cells == 0) return std::numeric_limits<double>::infinity();
  return part.bottom_m - h.max_m;
}

HumanoidWalker::HumanoidWalker(const HumanoidWalkerParams& params, const mapping::Heightmap& truth,
                               const Pose2& start_body, std::uint64_t seed)
    : params_(params), truth_(truth), rng_(seed) {
  params_.validate();
  if (!start_body.is_finite()) throw Error("HumanoidWalker: non-finite start pose");
  const double half = params_.body.nominal_separation_m / 2.0;
  for (Foot f : {Foot::kLeft, Foot::kRight}) {
    const Pose2 p = start_body * Pose2{0.0, f == Foot::kLeft ? half : -half, 0.0};
    double spread = 0.0;
    feet_[static_cast<int>(f)] = {p, sole_height(p, &spread), f};
    odom_[static_cast<int>(f)] = feet_[static_cast<int>(f)];
  }
}

SE3 HumanoidWalker::T_odom_base() const {
  return se3_from_pose2(body_between(odom_[0].pose, odom_[1].pose), odom_stance().z_m);
}

double support_ratio(const mapping::Heightmap& map, const Pose2& sole, double length_m, double width_m, double top_m,
                     double band_m) {
  const mapping::GridGeometry& g = map.geometry();
  const double c = std::cos(sole.theta), s = std::sin(sole.theta), hl = length_m / 2.0, hw = width_m / 2.0;
  const double r = std::hypot(hl, hw);
  const auto lo = g.world_to_cell_unbounded(sole.x - r, sole.y - r),
             hi = g.world_to_cell_unbounded(sole.x + r, sole.y + r);
  if (!lo || !hi) return 0.0;
  int cells = 0, supported = 0;
  for (int y = std::max(lo->y, 0); y <= std::min(hi->y, g.height - 1); ++y) {
    for (int x = std::max(lo->x, 0); x <= std::min(hi->x, g.width - 1); ++x) {
      const Eigen::Vector2d d = g.cell_center(x, y) - sole.position();
      if (std::abs(c * d.x() + s * d.y()) > hl || std::abs(-s * d.x() + c * d.y()) > hw || !map.known(x, y)) continue;
      ++cells;
      supported += map.height(x, y) >= top_m - band_m;
    }
  }
  return cells ? static_cast<double>(supported) / cells : 1.0;
}

double HumanoidWalker::sole_height(const Pose2& sole, double* spread, double* support) const {
  // The sole's rim (sole_edge_tolerance_m) may overhang an edge: it touches, it does not rest.
  const double shrink = 2.0 * params_.sole_edge_tolerance_m;
  const double l = std::max(params_.body.foot_length_m - shrink, 0.0),
               w = std::max(params_.body.foot_width_m - shrink, 0.0);
  const auto h = mapping::footprint_heights(truth_, sole, l, w);
  if (h.known_cells == 0) {
    *spread = 0.0;
    if (support) *support = 1.0;
    return 0.0;
  }
  *spread = h.max_m - h.min_m;
  if (support) *support = support_ratio(truth_, sole, l, w, h.max_m, params_.support_band_m);
  return h.max_m;
}

// Samples the swing sole along a segment while the foot at `fixed` stands,
// recording the deepest penetration per part and the smallest clearance.
void HumanoidWalker::sweep(const Segment& seg, const Pose2& fixed, double t0, double dt, StepExecution& out) const {
  const BodyModel& b = params_.body;
  const int n = params_.samples_per_segment;
  const Pose2 &from = seg.from, &to = seg.to;
  for (int k = 0; k <= n; ++k) {
    const double s = static_cast<double>(k) / n;
    const Pose2 foot{from.x + s * (to.x - from.x), from.y + s * (to.y - from.y),
                     normalize_angle(from.theta + s * angle_diff(to.theta, from.theta))};
    std::vector<BodyPart> parts = upper_body_parts(b, fixed, foot, seg.support_z_m);
    parts.push_back({"swing_foot", foot, b.foot_length_m, b.foot_width_m, seg.sole_z_m});
    for (const BodyPart& p : parts) {
      const double c = part_clearance_m(truth_, p);
      out.min_clearance_m = std::min(out.min_clearance_m, c);
      if (-c <= params_.collision_tolerance_m) continue;
      auto it = std::find_if(out.contacts.begin(), out.contacts.end(),
                             [&](const BodyContact& x) { return x.part == p.name; });
      if (it == out.contacts.end()) it = out.contacts.insert(out.contacts.end(), BodyContact{0.0, p.name, {}, 0.0});
      if (-c > it->penetration_m) *it = {t0 + s * dt, p.name, p.pose.position(), -c};
    }
  }
}

StepExecution HumanoidWalker::step(const StepCommand& cmd) {
  require(cmd.duration_s > 0.0 && cmd.peak_m > 0.0, "StepCommand.duration_s/peak_m", "> 0");
  if (!cmd.landing_in_stance.is_finite()) throw Error("HumanoidWalker::step: non-finite landing pose");
  const Footstep st = stance();
  Footstep& sw = feet_[1 - static_cast<int>(stance_)];
  const Pose2 noise{rng_.normal(0.0, params_.landing_noise_xy_m), rng_.normal(0.0, params_.landing_noise_xy_m),
                    rng_.normal(0.0, params_.landing_noise_yaw_rad)};
  const Pose2 target = st.pose * cmd.landing_in_stance * noise;
  StepExecution out;
  out.min_clearance_m = std::numeric_limits<double>::infinity();
  const double land_z = sole_height(target, &out.landing_spread_m, &out.support_ratio);
  const double side = stance_ == Foot::kLeft ? -1.0 : 1.0;
  const Pose2 via = st.pose * Pose2{0.0, side * params_.body.nominal_separation_m, 0.0};
  // The trailing foot rises and moves to the via point beside the stance foot (the upward phase
  // of the planner's previous action), then on to the landing pose (this action's downward
  // phase), and drops onto the terrain. A trailing foot higher than the stance foot (on the step
  // the stance foot came down from) stays that much higher on the way to the landing
  // (planning::footstep::build_inverse_heightmap's swing lift) rather than dropping at the via point.
  const double half = cmd.duration_s / 2.0;
  // The body is checked above the sole that supported it in the planner's model of each phase.
  sweep({sw.pose, via, sw.z_m + std::max(last_peak_m_, cmd.peak_m), sw.z_m}, st.pose, time_s_, half, out);
  sweep({via, target, std::max(st.z_m, sw.z_m) + cmd.peak_m, st.z_m}, st.pose, time_s_ + half, half, out);
  if (out.support_ratio < params_.min_support_ratio)  // the sole came down on an edge: the robot falls
    out.contacts.push_back({time_s_ + cmd.duration_s, "landing_foot", target.position(), out.landing_spread_m});

  // Kinematic odometry: the executed step relative to the stance foot, measured with noise.
  const Pose2 rel = st.pose.inverse() * target;
  const Pose2 odom_noise{rng_.normal(0.0, params_.odometry_noise_xy_m), rng_.normal(0.0, params_.odometry_noise_xy_m),
                         rng_.normal(0.0, params_.odometry_noise_yaw_rad)};
  const Footstep& odom_st = odom_stance();
  odom_[1 - static_cast<int>(stance_)] = {odom_st.pose * rel * odom_noise, odom_st.z_m + (land_z - st.z_m),
                                          other(stance_)};

  sw = {target, land_z, other(stance_)};
  stance_ = other(stance_);
  last_peak_m_ = cmd.peak_m;
  time_s_ += cmd.duration_s;
  out.landed = sw;
  return out;
}

}  // namespace bipednav::sim
