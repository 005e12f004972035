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

}  // namespace bipednav::perception
