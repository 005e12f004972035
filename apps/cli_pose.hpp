#pragma once

#include <string>

#include "bipednav/common/pose2.hpp"

namespace bipednav::app {

// Parses a pose option "x,y" or "x,y,yaw" (metres, radians; yaw 0 when omitted, or required
// with `yaw_required`). Throws bipednav::Error naming `option` for anything else or non-finite values.
Pose2 parse_pose(const std::string& text, const std::string& option, bool yaw_required = false);

}  // namespace bipednav::app
