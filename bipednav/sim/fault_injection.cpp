#include "bipednav/sim/fault_injection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace bipednav::sim {
namespace {

// Every second message of a source is stamped just before the message delivered before it.
constexpr double kReorderBack_s = 0.05;

}  // namespace

std::vector<TimedGoal> goals_with_floods(const std::vector<TimedGoal>& goals, const std::vector<Fault>& faults,
                                         const Bounds& bounds, std::uint64_t seed) {
  std::vector<TimedGoal> out = goals;
  Rng rng(seed ^ 0x9e3779b97f4a7c15ULL);
  for (const Fault& f : faults) {
    if (f.type != FaultType::GOAL_FLOOD) continue;
    const TimedGoal* in_force = nullptr;  // the scenario's goal at the flood's end
    for (const TimedGoal& g : goals)
      if (g.time_s <= f.end_s()) in_force = &g;
    for (int i = 0; i < f.goal_count; ++i) {
      const double t = f.start_s + f.duration_s * i / f.goal_count;
      out.push_back({t, Pose2{rng.uniform(bounds.min_x_m, bounds.max_x_m), rng.uniform(bounds.min_y_m, bounds.max_y_m),
                              rng.uniform(-M_PI, M_PI)}});
    }
    if (in_force) out.push_back({f.end_s(), in_force->pose});
  }
  std::stable_sort(out.begin(), out.end(), [](const TimedGoal& a, const TimedGoal& b) { return a.time_s < b.time_s; });
  return out;
}

FaultInjector::FaultInjector(std::vector<Fault> faults, std::uint64_t seed)
    : faults_(std::move(faults)), rng_(seed ^ 0xfa017ULL), jumped_(faults_.size(), false) {
  for (const Fault& f : faults_) f.validate();
}

const Fault* FaultInjector::find(FaultType type, double t_s) const {
  for (const Fault& f : faults_)
    if (f.type == type && f.active_at(t_s)) return &f;
  return nullptr;
}

bool FaultInjector::active(FaultType type, double t_s) const { return find(type, t_s) != nullptr; }

bool FaultInjector::has_sensor_faults() const {
  return std::any_of(faults_.begin(), faults_.end(), [](const Fault& f) {
    return f.type != FaultType::COMMAND_DROPOUT && f.type != FaultType::GOAL_FLOOD;
  });
}

bool FaultInjector::drops_command(double t_s) {
  if (!active(FaultType::COMMAND_DROPOUT, t_s)) return false;
  ++counters_.commands_dropped;
  return true;
}

void FaultInjector::corrupt_odometry(Odometry& odom) {
  const Pose2 truth = odom.T_odom_base;
  if (!last_true_odom_) {
    reported_odom_ = truth;
  } else {
    Pose2 d = last_true_odom_->inverse() * truth;
    if (const Fault* slip = find(FaultType::ODOMETRY_SLIP, odom.stamp_s)) {
      d = {slip->slip_scale * d.x, slip->slip_scale * d.y, slip->slip_scale * d.theta};
      odom.velocity = {slip->slip_scale * odom.velocity.linear_x, slip->slip_scale * odom.velocity.linear_y,
                       slip->slip_scale * odom.velocity.angular_z};
      ++counters_.odometry_slipped;
    }
    reported_odom_ = reported_odom_ * d;
  }
  last_true_odom_ = truth;
  for (std::size_t i = 0; i < faults_.size(); ++i) {
    if (faults_[i].type != FaultType::LOCALIZATION_JUMP || jumped_[i] || odom.stamp_s < faults_[i].start_s) continue;
    jumped_[i] = true;
    reported_odom_ = faults_[i].jump * reported_odom_;  // the odom frame itself jumps
    ++counters_.odometry_jumps;
  }
  odom.T_odom_base = reported_odom_;
}

void FaultInjector::delay(SensorFrame& frame, double delay_s) {
  if (frame.lidar) frame.lidar->stamp_s -= delay_s, ++counters_.messages_delayed;
  for (DepthCloud& d : frame.depth) d.cloud.stamp_s -= delay_s, ++counters_.messages_delayed;
  if (frame.odometry) frame.odometry->stamp_s -= delay_s, ++counters_.messages_delayed;
}

void FaultInjector::reorder(SensorFrame& frame) {
  // Every second message gets a stamp earlier than the previous delivery's.
  const auto swap_stamp = [&](double& stamp, std::optional<double>& last, bool& flip) {
    flip = !flip;
    if (flip && last) {
      stamp = *last - kReorderBack_s;
      ++counters_.messages_reordered;
    }
    last = stamp;
  };
  if (frame.odometry) swap_stamp(frame.odometry->stamp_s, last_odom_stamp_, flip_odom_);
  if (frame.lidar) swap_stamp(frame.lidar->stamp_s, last_sweep_stamp_, flip_sweep_);
  for (DepthCloud& d : frame.depth) swap_stamp(d.cloud.stamp_s, last_depth_stamp_[d.camera], flip_depth_[d.camera]);
}

SensorFrame FaultInjector::apply(SensorFrame frame) {
  const double t = frame.stamp_s;
  if (frame.lidar && active(FaultType::LIDAR_DROPOUT, t)) {
    frame.lidar.reset();
    ++counters_.sweeps_dropped;
  }
  if (const Fault* burst = find(FaultType::DEPTH_NAN_BURST, t)) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (DepthCloud& d : frame.depth)
      for (auto& p : d.cloud.points)
        if (burst->nan_fraction >= 1.0 || rng_.bernoulli(burst->nan_fraction)) {
          p = {nan, nan, nan};
          ++counters_.depth_points_nan;
        }
  }
  if (frame.odometry) corrupt_odometry(*frame.odometry);
  if (const Fault* stale = find(FaultType::STALE_TIMESTAMPS, t)) delay(frame, stale->delay_s);
  if (active(FaultType::OUT_OF_ORDER_TIMESTAMPS, t)) reorder(frame);
  return frame;
}

}  // namespace bipednav::sim
