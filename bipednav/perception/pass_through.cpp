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

PassThroughTest::PassThroughTest(const PassThroughParams& params, const Eigen::Vector3f& origin, const Plane& plane)
    : origin_(origin), plane_(normalize_plane(plane).cast<float>()) {
  params.validate();
  // Squared ranges in float; an infinite limit stays infinite.
  r2_min_ = static_cast<float>(params.min_range_m * params.min_range_m);
  r2_max_ = static_cast<float>(params.max_range_m * params.max_range_m);
  h_min_ = static_cast<float>(params.min_height_m);
  h_max_ = static_cast<float>(params.max_height_m);
}

PointCloud pass_through(const PointCloud& in, const PassThroughParams& params, const Eigen::Vector3f& origin,
                        const Plane& plane) {
  if (!in.is_consistent()) throw Error("pass_through: the cloud's optional fields do not match its point count");
  const PassThroughTest test(params, origin, plane);
  PointCloud out = in.empty_copy();
  if (!in.has_time() && !in.has_ring() && !in.has_intensity()) {
    for (const auto& p : in.points)
      if (test.keep(p)) out.points.push_back(p);
    return out;
  }
  for (std::size_t i = 0; i < in.size(); ++i)
    if (test.keep(in.points[i])) out.push_back_from(in, i);
  return out;
}

}  // namespace bipednav::perception
