#pragma once

#include <cstddef>

#include "bipednav/common/point_cloud.hpp"

namespace bipednav::perception {

// Depth decimation (librealsense's decimation filter, which D430 setups run before the voxel
// grid): an organised depth cloud (row-major, `width` points per row, NaN where the camera saw
// nothing) is cut into factor x factor pixel blocks, and each block keeps the point of the median
// range among its finite points (the lower median for an even count; librealsense takes the median
// depth for factors 2 and 3; a point whose squared range overflows a float counts as non-finite).
// Incomplete blocks at the right and bottom edges are dropped, as librealsense does. Points only;
// frame and stamp are copied. `out` is replaced (and must not be `in`). Returns the number of
// finite points of `in`. Throws Error when width < 1, factor is not in [1, 8] or the cloud is not
// a whole number of rows.
std::size_t decimate_depth(const PointCloud& in, int width, int factor, PointCloud& out);

struct DecimationCounts {
  std::size_t finite = 0;  // finite points of the input (decimate_depth's return value)
  std::size_t blocks = 0;  // points decimate_depth would output (before the range limit)
};

// decimate_depth fused with the depth range limit: `out` receives exactly the points that
// decimate_depth(in, width, factor, ...) outputs and PassThroughTest (pass_through.hpp) with
// max_range_m about the origin keeps (squared range p.squaredNorm() <= float(max_range_m^2)), in
// the same order, without the intermediate cloud. The block medians are picked by the squared
// ranges the limit needs anyway, and factor 2 handles four blocks per step. max_range_m may be
// infinite (no limit). Throws Error as decimate_depth, or for a max_range_m that is not > 0.
DecimationCounts decimate_depth_within(const PointCloud& in, int width, int factor, double max_range_m,
                                       PointCloud& out);

}  // namespace bipednav::perception
