#include "apps/cli_pose.hpp"

#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/io/number_list.hpp"

namespace bipednav::app {

Pose2 parse_pose(const std::string& text, const std::string& option, bool yaw_required) {
  const std::string expected = yaw_required ? "x,y,yaw" : "x,y or x,y,yaw";
  const auto fail = [&] { return Error(option + ": expected " + expected + " (metres, radians), got '" + text + "'"); };
  const std::vector<double> v = io::parse_number_list(text);
  if (v.size() != 3 && (yaw_required || v.size() != 2)) throw fail();
  return Pose2{v[0], v[1], v.size() == 3 ? v[2] : 0.0};
}

}  // namespace bipednav::app
