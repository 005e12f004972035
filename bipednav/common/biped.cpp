#include "bipednav/common/biped.hpp"

#include "bipednav/common/error.hpp"

namespace bipednav {

void BodyModel::validate() const {
  require(foot_length_m > 0 && foot_width_m > 0, "body.foot_length_m/foot_width_m", "> 0");
  require(nominal_separation_m > foot_width_m, "body.nominal_separation_m", "> foot_width_m (feet must not overlap)");
  require(ankle_height_m > 0 && hip_height_m > ankle_height_m, "body.hip_height_m", "> ankle_height_m > 0");
  require(torso_bottom_m > 0 && height_m > torso_bottom_m, "body.height_m", "> torso_bottom_m > 0");
  require(arm_bottom_m > 0 && arm_bottom_m < height_m, "body.arm_bottom_m", "in (0, height_m)");
}

}  // namespace bipednav
