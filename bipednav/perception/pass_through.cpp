#include "bipednav/perception/pass_through.hpp"

#include <cmath>

#include "bipednav/common/error.hpp"

namespace bipednav::perception {

void PassThroughParams::validate() const {
  require(min_range_m >= 0.0 && min_range_m <= max_range_m, "min_range_m", ">= 0 and <= max_range_m");
  require(max_range_m > 0.0, "max_range_m", "> 0 m (infinity disables the range limit)");
  require(!std::isnan(min_height_m) && !std::isnan(max_height_m) && min_height_m <= max_height_m, "min_height_m",
          "a number <= max_height_m");
}

std::vector<std::size_t> pass_through_indices(const std::vector<Eigen::Vector3f>& points,
                                              const PassThroughParams& params, const Eigen::Vector3f& origin,
                                              const Plane& plane) {
  params.validate();
  const Eigen::Vector4f pl = normalize_plane(plane).cast<float>();
  // Squared ranges in float; an infinite limit stays infinite.
  const float r2_min = static_cast<float>(params.min_range_m * params.min_range_m);
  const float r2_max = static_cast<float>(params.max_range_m * params.max_range_m);
  const float h_min = static_cast<float>(params.min_height_m), h_max = static_cast<float>(params.max_height_m);
  std::vector<std::size_t> keep;
  keep.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f& p = points[i];
    if (!p.allFinite()) continue;
    const float r2 = (p - origin).squaredNorm();
    const float h = signed_distance(pl, p);
    if (r2 >= r2_min && r2 <= r2_max && h >= h_min && h <= h_max) keep.push_back(i);
  }
  return keep;
}

PointCloud pass_through(const PointCloud& in, const PassThroughParams& params, const Eigen::Vector3f& origin,
                        const Plane& plane) {
  if (!in.is_consistent()) throw Error("pass_through: the cloud's optional fields do not match its point count");
  const auto keep = pass_through_indices(in.points, params, origin, plane);
  PointCloud out = in.empty_copy();
  out.reserve(keep.size());
  for (const std::size_t i : keep) out.push_back_from(in, i);
  return out;
}

}  // namespace bipednav::perception
