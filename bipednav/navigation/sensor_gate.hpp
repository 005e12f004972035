#pragma once

#include <map>
#include <string>
#include <vector>

#include "bipednav/common/sensor_frame.hpp"

namespace bipednav::navigation {

struct SensorGateParams {
  double max_age_s = 0.35;        // data stamped longer ago than this is stale (a sweep is ~0.1 s old)
  double min_valid_ratio = 0.05;  // a depth cloud with fewer finite points is a dropout
  double sensor_timeout_s = 0.5;  // a range sensor without valid data for this long is silent

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("max_age_s", max_age_s);
    v("min_valid_ratio", min_valid_ratio);
    v("sensor_timeout_s", sensor_timeout_s);
  }
};

struct SensorGateCounters {
  std::size_t stale = 0, out_of_order = 0, invalid = 0, frames_out_of_order = 0;
};

// Which parts of a frame the gate admitted, without copies of the clouds.
struct Admission {
  double stamp_s = 0.0;  // the frame's stamp; a frame from the past gets the previous frame's
  bool odometry = false, lidar = false;
  std::vector<std::uint8_t> depth;  // one per frame.depth entry: 1 = admitted
};

// Admits sensor data into the navigator: drops messages that are stale, stamped before the
// previous message of the same source, or not finite, and depth clouds that are (almost)
// all NaN; tracks when each range sensor last delivered valid data.
class SensorGate {
 public:
  // `lidar` names the LiDAR mount (empty: none); `depth_cameras` the depth mounts.
  SensorGate(SensorGateParams params, const std::string& lidar, const std::vector<std::string>& depth_cameras);

  // Which parts of `frame` are admitted (same stamp). Frames stamped before the previous frame
  // are dropped whole.
  Admission check(const SensorFrame& frame);
  // The admitted part of `frame` as a copy (check() plus the copies).
  SensorFrame admit(const SensorFrame& frame);
  // Every range sensor delivered valid data within the timeout (all count as fresh at start).
  bool all_alive(double now_s) const;
  // The range sensors that are silent now (for messages).
  std::vector<std::string> silent(double now_s) const;
  const SensorGateCounters& counters() const { return counters_; }

 private:
  bool fresh(double stamp_s, double now_s, double& last_s);

  SensorGateParams params_;
  std::string lidar_;
  std::map<std::string, double> last_valid_s_;  // per range sensor: admission time of its last valid data
  std::map<std::string, double> last_stamp_s_;  // per source: the last admitted stamp
  double last_frame_s_ = -1e300;
  bool started_ = false;
  SensorGateCounters counters_;
};

}  // namespace bipednav::navigation
