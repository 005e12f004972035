#include "bipednav/planning/local/teb_terms.hpp"

namespace bipednav::planning::local {

double nonholonomic_error(double x1, double y1, double th1, double x2, double y2, double th2) {
  return nonholonomic_error<double>(x1, y1, th1, x2, y2, th2);
}

double exact_linear_velocity(double x1, double y1, double th1, double x2, double y2, double dt) {
  const double dx = x2 - x1, dy = y2 - y1;
  const double forward = std::cos(th1) * dx + std::sin(th1) * dy;
  const double v = std::hypot(dx, dy) / dt;
  return forward < 0.0 ? -v : v;
}

}  // namespace bipednav::planning::local
