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
  // The kept points written in place (room for all, trimmed after), their source ids after them.
  const std::size_t first = out.cloud.size();
  out.cloud.points.resize(first + in.size());
  Eigen::Vector3f* o = out.cloud.points.data() + first;
  for (const Eigen::Vector3f& p : in.points) {
    if (!p.allFinite() || (crop && !crop->keep(p))) continue;
    *o++ = R * p + t;
  }
  const auto kept = static_cast<std::size_t>(o - (out.cloud.points.data() + first));
  out.cloud.points.resize(first + kept);
  out.source.resize(out.source.size() + kept, id);
  return id;
}

}  // namespace bipednav::perception
