#include "bipednav/tracking/association.hpp"

#include <cmath>
#include <limits>

#include "bipednav/tracking/hungarian.hpp"

namespace bipednav::tracking {

std::vector<int> associate(const std::vector<const TrackFilter*>& tracks, const std::vector<Detection>& detections,
                           double gate_chi2) {
  const auto n = static_cast<Eigen::Index>(tracks.size()), m = static_cast<Eigen::Index>(detections.size());
  Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(n, m, std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < m; ++j) {
      const Detection& d = detections[static_cast<std::size_t>(j)];
      if (!d.finite()) continue;
      const Innovation in = tracks[static_cast<std::size_t>(i)]->innovation(d.position, d.covariance);
      const double det = in.S.determinant();
      if (!(det > 0.0) || !std::isfinite(det)) continue;
      const double d2 = in.mahalanobis2();
      if (d2 <= gate_chi2) cost(i, j) = d2 + std::log(det);
    }
  }
  return solve_assignment(cost);
}

}  // namespace bipednav::tracking
