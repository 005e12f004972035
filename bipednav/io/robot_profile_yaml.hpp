#pragma once

#include <filesystem>
#include <string>

#include "bipednav/common/robot_profile.hpp"
#include "bipednav/io/param_reader.hpp"

namespace bipednav::io {

// Robot profiles (config/*.yaml). Keys are the RobotProfile field names; `sensors` is a list
// of mounts with keys name, type, x_m, y_m, z_m, roll_rad, pitch_rad, yaw_rad. Absent keys keep
// the struct defaults; unknown keys and wrong types raise FileError naming the file, line and
// field; the result is validate()d (a violation becomes a FileError naming the file and the field).
RobotProfile read_robot_profile(ParamReader& reader);
RobotProfile load_robot_profile(const std::filesystem::path& file);
RobotProfile parse_robot_profile(const std::string& yaml, const std::string& name = "<string>");

}  // namespace bipednav::io
