#pragma once

#include "bipednav/common/velocity_limits.hpp"

namespace bipednav::test {

// Forward/yaw-only command limits, each value by name at the one place they are spelt out.
inline VelocityLimits forward_yaw_limits(double max_vel_x_mps, double max_vel_x_backwards_mps,
                                         double max_vel_theta_radps, double acc_lim_x_mps2,
                                         double acc_lim_theta_radps2) {
  return {.max_vel_x_mps = max_vel_x_mps,
          .max_vel_x_backwards_mps = max_vel_x_backwards_mps,
          .max_vel_theta_radps = max_vel_theta_radps,
          .acc_lim_x_mps2 = acc_lim_x_mps2,
          .acc_lim_theta_radps2 = acc_lim_theta_radps2};
}

}  // namespace bipednav::test
