#include "bipednav/perception/lidar_model.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/error.hpp"

namespace bipednav::perception {

namespace {

// n beams evenly from lo_deg to hi_deg (inclusive), appended.
void uniform_beams(std::vector<double>& out, int n, double lo_deg, double hi_deg) {
  for (int i = 0; i < n; ++i) out.push_back(deg2rad(lo_deg + (hi_deg - lo_deg) * i / (n - 1)));
}

}  // namespace

void LidarModel::validate() const {
  require(!elevations_rad.empty(), "elevations_rad", "at least one beam");
  require(std::is_sorted(elevations_rad.begin(), elevations_rad.end()) &&
              std::adjacent_find(elevations_rad.begin(), elevations_rad.end()) == elevations_rad.end(),
          "elevations_rad", "strictly ascending");
  require(elevations_rad.size() <= 1024, "elevations_rad", "at most 1024 beams");
  require(rate_hz > 0.0 && std::isfinite(rate_hz), "rate_hz", "> 0");
}

std::vector<std::string> lidar_model_names() { return {"vlp16", "hdl32", "hdl64", "os0-64"}; }

LidarModel lidar_model(const std::string& name) {
  LidarModel m;
  m.name = name;
  if (name == "vlp16") {
    uniform_beams(m.elevations_rad, 16, -15.0, 15.0);
  } else if (name == "hdl32") {
    uniform_beams(m.elevations_rad, 32, -30.67, 10.67);
  } else if (name == "hdl64") {
    uniform_beams(m.elevations_rad, 32, -24.33, -8.83);  // lower block
    uniform_beams(m.elevations_rad, 32, -8.33, 2.0);     // upper block
    m.table_assigns_rings = false;
  } else if (name == "os0-64") {
    uniform_beams(m.elevations_rad, 64, -45.0, 45.0);
  } else {
    std::string known;
    for (const auto& n : lidar_model_names()) known += (known.empty() ? "" : ", ") + n;
    throw Error("unknown LiDAR model '" + name + "' (known: " + known + ")");
  }
  m.validate();
  return m;
}

}  // namespace bipednav::perception
