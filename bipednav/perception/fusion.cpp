#include "bipednav/perception/fusion.hpp"

#include "bipednav/common/error.hpp"

namespace bipednav::perception {

std::size_t append_sensor_cloud(FusedCloud& out, const PointCloud& in, const SE3& T_base_sensor,
                                const std::string& name, double max_range_m, const PassThroughTest* crop) {
  if (out.sources.size() >= 255) throw Error("fusion: more than 255 sensor sources");
  const auto id = static_cast<std::uint8_t>(out.sources.size());
  out.sources.push_back({name, T_base_sensor.translation(), max_range_m});
  const Eigen::Matrix3f R = T_base_sensor.linear().cast<float>();
  const Eigen::Vector3f t = T_base_sensor.translation().cast<float>();
  out.cloud.points.reserve(out.cloud.size() + in.size());
  out.source.reserve(out.cloud.size() + in.size());
  for (const Eigen::Vector3f& p : in.points) {
    if (!p.allFinite() || (crop && !crop->keep(p))) continue;
    out.cloud.points.push_back(R * p + t);
    out.source.push_back(id);
  }
  return id;
}

}  // namespace bipednav::perception
