#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace bipednav {

// A point cloud: xyz plus optional per-point fields. `time_offsets_s` (seconds since `stamp_s`,
// the firing time of each point) and `rings` (laser index) are either empty or one per point.
struct PointCloud {
  std::vector<Eigen::Vector3f> points;
  std::vector<float> time_offsets_s;
  std::vector<std::uint16_t> rings;
  std::vector<float> intensities;
  std::string frame_id;
  double stamp_s = 0.0;

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool has_time() const { return !time_offsets_s.empty(); }
  bool has_ring() const { return !rings.empty(); }
  bool has_intensity() const { return !intensities.empty(); }

  void reserve(std::size_t n) { points.reserve(n); }
  void clear() {
    points.clear();
    time_offsets_s.clear();
    rings.clear();
    intensities.clear();
  }
  // Copies point i of `other` (with whichever optional fields both clouds carry).
  void push_back_from(const PointCloud& other, std::size_t i) {
    points.push_back(other.points[i]);
    if (other.has_time()) time_offsets_s.push_back(other.time_offsets_s[i]);
    if (other.has_ring()) rings.push_back(other.rings[i]);
    if (other.has_intensity()) intensities.push_back(other.intensities[i]);
  }
  // Metadata only (frame, stamp), no points.
  PointCloud empty_copy() const {
    PointCloud c;
    c.frame_id = frame_id;
    c.stamp_s = stamp_s;
    return c;
  }
  // True when every optional field is empty or matches the point count.
  bool is_consistent() const {
    const auto ok = [&](std::size_t n) { return n == 0 || n == points.size(); };
    return ok(time_offsets_s.size()) && ok(rings.size()) && ok(intensities.size());
  }
};

}  // namespace bipednav
