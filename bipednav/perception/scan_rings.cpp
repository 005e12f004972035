#include "bipednav/perception/scan_rings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "bipednav/common/error.hpp"

namespace bipednav::perception {

namespace {

double elevation_of(const Eigen::Vector3f& p) {
  return std::atan2(static_cast<double>(p.z()), std::hypot(static_cast<double>(p.x()), static_cast<double>(p.y())));
}

// Index of the value of `sorted` (ascending, non-empty) nearest to v.
std::uint16_t nearest_index(const std::vector<double>& sorted, double v) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), v);
  if (it == sorted.begin()) return 0;
  if (it == sorted.end()) return static_cast<std::uint16_t>(sorted.size() - 1);
  const auto i = static_cast<std::size_t>(it - sorted.begin());
  return static_cast<std::uint16_t>(v - sorted[i - 1] <= sorted[i] - v ? i - 1 : i);
}

void check_table(const std::vector<double>& elevations_rad) {
  if (elevations_rad.empty() || elevations_rad.size() > 65536 ||
      !std::is_sorted(elevations_rad.begin(), elevations_rad.end()))
    throw Error("ring reconstruction: expected an ascending table of 1..65536 beam elevations");
}

std::size_t ring_count_of(const std::vector<std::uint16_t>& rings) {
  return rings.empty() ? 0 : static_cast<std::size_t>(*std::max_element(rings.begin(), rings.end())) + 1;
}

}  // namespace

std::vector<std::uint16_t> rings_from_beam_table(const PointCloud& sweep, const std::vector<double>& elevations_rad) {
  check_table(elevations_rad);
  std::vector<std::uint16_t> rings(sweep.size(), 0);
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const double e = elevation_of(sweep.points[i]);
    if (std::isfinite(e)) rings[i] = nearest_index(elevations_rad, e);
  }
  return rings;
}

std::vector<std::uint16_t> rings_from_scan_order(const PointCloud& sweep, std::size_t min_line_points,
                                                 std::size_t& lines) {
  constexpr double kPi = std::numbers::pi;
  std::vector<double> az(sweep.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t i = 0; i < sweep.size(); ++i)
    if (sweep.points[i].allFinite()) az[i] = std::atan2(sweep.points[i].y(), sweep.points[i].x());
  // The direction of the lines: the sign of most small steps between consecutive points.
  std::size_t up = 0, down = 0;
  for (std::size_t i = 1; i < az.size(); ++i) {
    const double d = az[i] - az[i - 1];
    if (d > 0.0 && d < 0.1) ++up;
    if (d < 0.0 && d > -0.1) ++down;
  }
  const double sign = up >= down ? 1.0 : -1.0;
  std::vector<std::uint16_t> rings(sweep.size(), 0);
  std::size_t line = 0, in_line = 0;
  double last = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < az.size(); ++i) {
    if (std::isfinite(az[i])) {
      if (std::isfinite(last) && sign * (az[i] - last) < -kPi && in_line >= min_line_points && line < 65535) {
        ++line;
        in_line = 0;
      }
      last = az[i];
    }
    rings[i] = static_cast<std::uint16_t>(line);
    ++in_line;
  }
  lines = sweep.empty() ? 0 : line + 1;
  return rings;
}

namespace {

// Optimal 1D k-means of weighted values (ascending) by dynamic programming (Wang and Song, "Ckmeans.1d.dp",
// R Journal 2011): D[m][j] = min over i of D[m-1][i-1] + SSE(i..j), the split i monotone in j, so
// each layer is filled by divide and conquer in O(n log n). Returns the first value of each cluster.
class KMeans1d {
 public:
  KMeans1d(const std::vector<double>& x, const std::vector<double>& w) : n_(x.size()) {
    s0_.assign(n_ + 1, 0.0);
    s1_.assign(n_ + 1, 0.0);
    s2_.assign(n_ + 1, 0.0);
    for (std::size_t i = 0; i < n_; ++i) {
      s0_[i + 1] = s0_[i] + w[i];
      s1_[i + 1] = s1_[i] + w[i] * x[i];
      s2_[i + 1] = s2_[i] + w[i] * x[i] * x[i];
    }
  }

  std::vector<std::size_t> cluster_starts(std::size_t k) {
    k = std::min(k, n_);
    std::vector<double> prev(n_), cur(n_);
    split_.assign(k, std::vector<std::size_t>(n_, 0));
    for (std::size_t j = 0; j < n_; ++j) prev[j] = sse(0, j);
    for (std::size_t m = 1; m < k; ++m) {
      std::fill(cur.begin(), cur.end(), std::numeric_limits<double>::infinity());
      fill(m, m, n_ - 1, m, n_ - 1, prev, cur);
      std::swap(prev, cur);
    }
    std::vector<std::size_t> starts(k, 0);
    std::size_t j = n_ - 1;
    for (std::size_t m = k; m-- > 1;) {
      starts[m] = split_[m][j];
      j = starts[m] - 1;
    }
    return starts;
  }

 private:
  double sse(std::size_t i, std::size_t j) const {  // of values i..j
    const double s0 = s0_[j + 1] - s0_[i];
    if (s0 <= 0.0) return 0.0;
    const double s1 = s1_[j + 1] - s1_[i];
    return std::max(0.0, (s2_[j + 1] - s2_[i]) - s1 * s1 / s0);
  }

  // cur[j] for j in [jlo, jhi], knowing the optimal start lies in [ilo, ihi].
  void fill(std::size_t m, std::size_t jlo, std::size_t jhi, std::size_t ilo, std::size_t ihi,
            const std::vector<double>& prev, std::vector<double>& cur) {
    if (jlo > jhi) return;
    const std::size_t j = jlo + (jhi - jlo) / 2;
    std::size_t best = std::max(ilo, m);
    double best_cost = std::numeric_limits<double>::infinity();
    for (std::size_t i = std::max(ilo, m); i <= std::min(ihi, j); ++i) {
      const double c = prev[i - 1] + sse(i, j);
      if (c < best_cost) {
        best_cost = c;
        best = i;
      }
    }
    cur[j] = best_cost;
    split_[m][j] = best;
    if (j > jlo) fill(m, jlo, j - 1, ilo, best, prev, cur);
    fill(m, j + 1, jhi, best, ihi, prev, cur);
  }

  std::size_t n_;
  std::vector<double> s0_, s1_, s2_;
  std::vector<std::vector<std::size_t>> split_;
};

}  // namespace

std::vector<std::uint16_t> rings_from_elevation_clusters(const PointCloud& sweep, std::size_t beams) {
  if (beams < 1 || beams > 65536) throw Error("ring reconstruction: expected 1..65536 beams");
  // Histogram of the elevations in 0.01 deg bins; the non-empty bins are clustered.
  constexpr double kBinRad = 0.01 * std::numbers::pi / 180.0;
  std::vector<long> bin(sweep.size(), std::numeric_limits<long>::min());
  long lo = std::numeric_limits<long>::max(), hi = std::numeric_limits<long>::min();
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const double e = elevation_of(sweep.points[i]);
    if (!std::isfinite(e)) continue;
    bin[i] = std::lround(e / kBinRad);
    lo = std::min(lo, bin[i]);
    hi = std::max(hi, bin[i]);
  }
  std::vector<std::uint16_t> rings(sweep.size(), 0);
  if (lo > hi) return rings;
  std::vector<double> weight(static_cast<std::size_t>(hi - lo) + 1, 0.0);
  for (const long b : bin)
    if (b != std::numeric_limits<long>::min()) weight[static_cast<std::size_t>(b - lo)] += 1.0;
  std::vector<double> x, w;
  std::vector<std::size_t> dense(weight.size(), 0);  // histogram bin -> index among the non-empty
  for (std::size_t b = 0; b < weight.size(); ++b) {
    dense[b] = x.size();
    if (weight[b] == 0.0) continue;
    x.push_back(static_cast<double>(b));
    w.push_back(weight[b]);
  }
  const std::vector<std::size_t> starts = KMeans1d(x, w).cluster_starts(beams);
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    if (bin[i] == std::numeric_limits<long>::min()) continue;
    const std::size_t d = dense[static_cast<std::size_t>(bin[i] - lo)];
    const auto it = std::upper_bound(starts.begin(), starts.end(), d);
    rings[i] = static_cast<std::uint16_t>(it - starts.begin() - 1);
  }
  return rings;
}

std::string to_string(RingMethod m) {
  switch (m) {
    case RingMethod::from_cloud:
      return "from_cloud";
    case RingMethod::beam_table:
      return "beam_table";
    case RingMethod::scan_order:
      return "scan_order";
    case RingMethod::elevation_clusters:
      return "elevation_clusters";
  }
  return "?";
}

RingReconstruction reconstruct_rings(const PointCloud& sweep, const LidarModel& model) {
  model.validate();
  RingReconstruction r;
  if (sweep.has_ring()) {
    r.rings = sweep.rings;
    r.method = RingMethod::from_cloud;
  } else if (model.table_assigns_rings) {
    r.rings = rings_from_beam_table(sweep, model.elevations_rad);
    r.method = RingMethod::beam_table;
  } else {
    const std::size_t beams = model.elevations_rad.size();
    std::size_t lines = 0;
    r.rings = rings_from_scan_order(sweep, std::max<std::size_t>(1, sweep.size() / (4 * beams)), lines);
    r.method = RingMethod::scan_order;
    const double b = static_cast<double>(beams), l = static_cast<double>(lines);
    if (l < 0.9 * b || l > 1.1 * b + 1.0) {
      r.rings = rings_from_elevation_clusters(sweep, beams);
      r.method = RingMethod::elevation_clusters;
    }
  }
  r.ring_count = ring_count_of(r.rings);
  return r;
}

}  // namespace bipednav::perception
