#include "bipednav/navigation/sensor_gate.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::navigation {
namespace {

constexpr const char* kOdometry = "odometry";
constexpr const char* kLidar = "lidar";

// At least `min_ratio` of the points are finite (counting stops once that is certain).
bool enough_valid(const PointCloud& cloud, double min_ratio) {
  const std::size_t n = cloud.points.size();
  if (n == 0) return min_ratio <= 0.0;
  const double need = min_ratio * static_cast<double>(n);
  std::size_t finite = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (static_cast<double>(finite) >= need) return true;
    finite += cloud.points[i].allFinite() ? 1 : 0;
  }
  return static_cast<double>(finite) >= need;
}

}  // namespace

void SensorGateParams::validate() const {
  require(max_age_s > 0.0, "sensor_gate.max_age_s", "> 0");
  require(min_valid_ratio >= 0.0 && min_valid_ratio <= 1.0, "sensor_gate.min_valid_ratio", "in [0, 1]");
  require(sensor_timeout_s > 0.0, "sensor_gate.sensor_timeout_s", "> 0");
}

SensorGate::SensorGate(SensorGateParams params, const std::string& lidar, const std::vector<std::string>& depth_cameras)
    : params_(params), lidar_(lidar) {
  params_.validate();
  if (!lidar_.empty()) last_valid_s_[lidar_] = -1e300;
  for (const auto& name : depth_cameras) last_valid_s_[name] = -1e300;
}

bool SensorGate::fresh(double stamp_s, double now_s, double& last_s) {
  if (!std::isfinite(stamp_s)) {
    ++counters_.invalid;
    return false;
  }
  if (stamp_s <= last_s) {
    ++counters_.out_of_order;
    return false;
  }
  if (now_s - stamp_s > params_.max_age_s) {
    ++counters_.stale;
    return false;
  }
  last_s = stamp_s;
  return true;
}

Admission SensorGate::check(const SensorFrame& frame) {
  Admission out;
  out.stamp_s = frame.stamp_s;
  out.depth.assign(frame.depth.size(), 0);
  if (!std::isfinite(frame.stamp_s) || frame.stamp_s < last_frame_s_) {
    ++counters_.frames_out_of_order;
    out.stamp_s = last_frame_s_;
    return out;
  }
  last_frame_s_ = frame.stamp_s;
  if (!started_) {  // sensors count as alive from the first frame: a sweep takes a while
    for (auto& [name, t] : last_valid_s_) t = frame.stamp_s;
    started_ = true;
  }
  const double now = frame.stamp_s;
  if (frame.odometry) {
    auto& last = last_stamp_s_.try_emplace(kOdometry, -1e300).first->second;
    out.odometry = fresh(frame.odometry->stamp_s, now, last);
  }
  if (frame.lidar) {
    auto& last = last_stamp_s_.try_emplace(kLidar, -1e300).first->second;
    if (fresh(frame.lidar->stamp_s, now, last)) {
      out.lidar = true;
      if (!lidar_.empty()) last_valid_s_[lidar_] = now;
    }
  }
  for (std::size_t i = 0; i < frame.depth.size(); ++i) {
    const DepthCloud& d = frame.depth[i];
    auto& last = last_stamp_s_.try_emplace("depth:" + d.camera, -1e300).first->second;
    if (!fresh(d.cloud.stamp_s, now, last)) continue;
    if (!enough_valid(d.cloud, params_.min_valid_ratio)) {
      ++counters_.invalid;
      continue;
    }
    out.depth[i] = 1;
    if (auto it = last_valid_s_.find(d.camera); it != last_valid_s_.end()) it->second = now;
  }
  return out;
}

SensorFrame SensorGate::admit(const SensorFrame& frame) {
  const Admission a = check(frame);
  SensorFrame out;
  out.stamp_s = a.stamp_s;
  if (a.odometry) out.odometry = frame.odometry;
  if (a.lidar) out.lidar = frame.lidar;
  for (std::size_t i = 0; i < frame.depth.size(); ++i)
    if (a.depth[i]) out.depth.push_back(frame.depth[i]);
  return out;
}

bool SensorGate::all_alive(double now_s) const { return silent(now_s).empty(); }

std::vector<std::string> SensorGate::silent(double now_s) const {
  std::vector<std::string> out;
  for (const auto& [name, t] : last_valid_s_)
    if (now_s - t > params_.sensor_timeout_s) out.push_back(name);
  return out;
}

}  // namespace bipednav::navigation
