#pragma once

#include <string>
#include <vector>

namespace bipednav::perception {

// A spinning multi-beam LiDAR: its beams' nominal elevation angles and its rotation. Used to give
// recorded sweeps that carry only x, y, z a ring (laser index) and a firing time per point.
struct LidarModel {
  std::string name;
  std::vector<double> elevations_rad;  // nominal, ascending: ring 0 is the lowest beam
  // The nominal table assigns rings by nearest elevation. False where the beams' elevations seen
  // from the sensor origin vary with range (the HDL-64E's lasers sit in two blocks ~0.2 m apart
  // in height, and its table is per-unit calibration): rings come from the stream order or from
  // clusters of the measured elevations instead (scan_rings.hpp).
  bool table_assigns_rings = true;
  double rate_hz = 10.0;  // revolutions per second (one sweep each)
  bool clockwise = true;  // seen from above (z up): azimuth decreases with time, as Velodynes spin
  void validate() const;
};

// The known models: "vlp16" (16 beams, -15..+15 deg in 2 deg steps), "hdl32" (32 beams,
// -30.67..+10.67 deg in 4/3 deg steps), "hdl64" (HDL-64E nominal: 32 beams +2..-8.33 deg in 1/3
// deg steps above 32 beams -8.83..-24.33 deg in 1/2 deg steps), "os0-64" (Ouster OS0, 64 beams
// uniform over -45..+45 deg). Throws Error listing them for any other name.
LidarModel lidar_model(const std::string& name);
std::vector<std::string> lidar_model_names();

}  // namespace bipednav::perception
