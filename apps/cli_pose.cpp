#include "apps/cli_pose.hpp"

#include <sstream>
#include <stdexcept>
#include <vector>

#include "bipednav/common/error.hpp"

namespace bipednav::app {

Pose2 parse_pose(const std::string& text, const std::string& option, bool yaw_required) {
  const std::string expected = yaw_required ? "x,y,yaw" : "x,y or x,y,yaw";
  const auto fail = [&] { return Error(option + ": expected " + expected + " (metres, radians), got '" + text + "'"); };
  std::vector<double> v;
  std::stringstream ss(text);
  std::string part;
  while (std::getline(ss, part, ',')) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(part, &used));
      if (used != part.size()) throw std::invalid_argument(part);
    } catch (const std::exception&) {
      throw fail();
    }
  }
  if (v.size() != 3 && (yaw_required || v.size() != 2)) throw fail();
  const Pose2 p{v[0], v[1], v.size() == 3 ? v[2] : 0.0};
  if (!p.is_finite()) throw fail();
  return p;
}

}  // namespace bipednav::app
