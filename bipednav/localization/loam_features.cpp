#include "bipednav/localization/loam_features.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "bipednav/common/error.hpp"

namespace bipednav::localization {

namespace {

// The ranges of one ring's points and the gaps between neighbours (gap[i] = |p[i+1] - p[i]|),
// computed once: the marking below reads each several times.
struct RingGeometry {
  std::vector<float> range, gap;
  explicit RingGeometry(const std::vector<Eigen::Vector3f>& pts) : range(pts.size()), gap(pts.size(), 0.0f) {
    for (std::size_t i = 0; i < pts.size(); ++i) range[i] = pts[i].norm();
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) gap[i] = (pts[i + 1] - pts[i]).norm();
  }
};

// Marks points whose smoothness is unreliable (section 4.4.1): the occluded side of a depth
// discontinuity, both sides of a gap without returns, and surfaces nearly parallel to the beam.
void mark_unreliable(const RingGeometry& ring, const FeatureParams& p, std::vector<char>& picked) {
  const int n = static_cast<int>(ring.range.size());
  const int k = p.neighbours_per_side;
  const auto mark = [&](int from, int to) {
    for (int i = std::max(0, from); i <= std::min(n - 1, to); ++i) picked[static_cast<std::size_t>(i)] = 1;
  };
  for (int i = 0; i + 1 < n; ++i) {
    const float di = ring.range[static_cast<std::size_t>(i)], dj = ring.range[static_cast<std::size_t>(i) + 1];
    const float gap = ring.gap[static_cast<std::size_t>(i)];
    const float near = std::min(di, dj);
    if (std::abs(di - dj) > p.occlusion_ratio * near) {
      if (di > dj)
        mark(i - k, i);  // the farther side is occluded by the nearer object
      else
        mark(i + 1, i + 1 + k);
    } else if (gap > p.max_neighbour_gap_ratio * near) {
      mark(i - k + 1, i + k);
    }
  }
  for (int i = 1; i + 1 < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const float r = ring.range[u];
    if (ring.gap[u - 1] > p.parallel_beam_ratio * r && ring.gap[u] > p.parallel_beam_ratio * r) picked[u] = 1;
  }
}

// Marks the neighbours of a selected point so features spread out, stopping at gaps.
void mark_neighbours(const RingGeometry& ring, int i, const FeatureParams& p, std::vector<char>& picked) {
  const int n = static_cast<int>(ring.range.size());
  const float limit = static_cast<float>(p.max_neighbour_gap_ratio) * ring.range[static_cast<std::size_t>(i)];
  for (int dir : {-1, 1}) {
    for (int l = 1; l <= p.neighbours_per_side; ++l) {
      const int j = i + dir * l, prev = j - dir;
      if (j < 0 || j >= n) break;
      if (ring.gap[static_cast<std::size_t>(std::min(j, prev))] > limit) break;
      picked[static_cast<std::size_t>(j)] = 1;
    }
  }
}

struct RegionSelection {
  std::vector<int> sharp, map;
};

// Picks up to max and max * factor points of one sub-region from `candidates` (the points past
// the threshold), best first (highest smoothness c for edges, lowest for planars). The selection
// usually runs through most candidates, so they are sorted whole, with their scores beside them.
// Candidates already picked (unreliable, or next to a selected feature) are skipped wherever they
// come, so only the others are sorted. Equal scores keep the order a chunked partial sort of
// `candidates` gives them (the order these features were selected in before; ties are rare), so
// that path stays for them.
RegionSelection select(std::vector<int>& candidates, const std::vector<double>& c, bool edges, const RingGeometry& ring,
                       const FeatureParams& p, std::vector<char>& picked, std::vector<std::pair<double, int>>& scored) {
  RegionSelection sel;
  const int max_sharp = edges ? p.max_edges_per_region : p.max_planars_per_region;
  const auto max_map = static_cast<std::size_t>(max_sharp * p.map_feature_factor);
  const auto consider = [&](int i) {
    if (picked[static_cast<std::size_t>(i)]) return;
    if (static_cast<int>(sel.sharp.size()) < max_sharp) sel.sharp.push_back(i);
    sel.map.push_back(i);
    picked[static_cast<std::size_t>(i)] = 1;
    mark_neighbours(ring, i, p, picked);
  };
  scored.clear();
  for (const int i : candidates) {
    if (picked[static_cast<std::size_t>(i)]) continue;  // skipped wherever it would come
    const double ci = c[static_cast<std::size_t>(i)];
    scored.emplace_back(edges ? -ci : ci, i);  // ascending: best first
  }
  std::sort(scored.begin(), scored.end());
  bool ties = false;
  for (std::size_t n = 1; n < scored.size() && !ties; ++n) ties = scored[n - 1].first == scored[n].first;
  if (!ties) {
    for (std::size_t n = 0; n < scored.size() && sel.map.size() < max_map; ++n) consider(scored[n].second);
    return sel;
  }
  const auto better = [&](int a, int b) {
    const double ca = c[static_cast<std::size_t>(a)], cb = c[static_cast<std::size_t>(b)];
    return edges ? ca > cb : ca < cb;
  };
  std::size_t sorted = 0;
  for (std::size_t n = 0; n < candidates.size() && sel.map.size() < max_map; ++n) {
    if (n == sorted) {
      const std::size_t chunk = std::min(candidates.size() - sorted, std::max<std::size_t>(2 * max_map, 16));
      const auto first = candidates.begin() + static_cast<std::ptrdiff_t>(sorted);
      const auto middle = first + static_cast<std::ptrdiff_t>(chunk);
      std::partial_sort(first, middle, candidates.end(), better);
      sorted += chunk;
    }
    consider(candidates[n]);
  }
  return sel;
}

void process_ring(const PointCloud& sweep, const std::vector<std::uint32_t>& idx, const FeatureParams& p,
                  LoamFeatures& out) {
  const int k = p.neighbours_per_side;
  const int n = static_cast<int>(idx.size());
  if (n < 2 * k + 1) return;
  std::vector<Eigen::Vector3f> pts(idx.size());
  for (std::size_t i = 0; i < idx.size(); ++i) pts[i] = sweep.points[idx[i]];
  const std::vector<double> c = ring_smoothness(pts, k);
  std::vector<char> picked(idx.size(), 0);
  const RingGeometry ring(pts);
  mark_unreliable(ring, p, picked);
  std::vector<int> sharp, flat;
  std::vector<std::pair<double, int>> scored;
  for (int r = 0; r < p.sub_regions; ++r) {
    const int begin = k + (n - 2 * k) * r / p.sub_regions;
    const int end = k + (n - 2 * k) * (r + 1) / p.sub_regions;
    // Edges: the sharpest points above edge_threshold; planars: the flattest below
    // planar_threshold (points without a smoothness, c < 0, are neither).
    sharp.clear();
    flat.clear();
    for (int i = begin; i < end; ++i) {
      const double ci = c[static_cast<std::size_t>(i)];
      if (ci > p.edge_threshold)
        sharp.push_back(i);
      else if (ci >= 0.0 && ci < p.planar_threshold)
        flat.push_back(i);
    }
    const RegionSelection e = select(sharp, c, true, ring, p, picked, scored);
    const RegionSelection f = select(flat, c, false, ring, p, picked, scored);
    for (int i : e.sharp) out.edges.push_back_from(sweep, idx[static_cast<std::size_t>(i)]);
    for (int i : e.map) out.map_edges.push_back_from(sweep, idx[static_cast<std::size_t>(i)]);
    for (int i : f.sharp) out.planars.push_back_from(sweep, idx[static_cast<std::size_t>(i)]);
    for (int i : f.map) out.map_planars.push_back_from(sweep, idx[static_cast<std::size_t>(i)]);
  }
}

}  // namespace

void FeatureParams::validate() const {
  require(neighbours_per_side >= 1 && neighbours_per_side <= 20, "neighbours_per_side", "in [1, 20]");
  require(sub_regions >= 1, "sub_regions", ">= 1");
  require(max_edges_per_region >= 0, "max_edges_per_region", ">= 0");
  require(max_planars_per_region >= 1, "max_planars_per_region", ">= 1");
  require(map_feature_factor >= 1, "map_feature_factor", ">= 1");
  require(edge_threshold > planar_threshold && planar_threshold > 0.0, "edge_threshold", "> planar_threshold > 0");
  require(min_range_m >= 0.0 && max_range_m > min_range_m, "max_range_m", "> min_range_m >= 0");
  require(occlusion_ratio > 0.0, "occlusion_ratio", "> 0");
  require(parallel_beam_ratio > 0.0, "parallel_beam_ratio", "> 0");
  require(max_neighbour_gap_ratio > 0.0, "max_neighbour_gap_ratio", "> 0");
  require(rings >= 1 && rings <= 1024, "rings", "in [1, 1024]");
  require(max_elevation_rad > min_elevation_rad, "max_elevation_rad", "> min_elevation_rad");
}

std::vector<double> ring_smoothness(const std::vector<Eigen::Vector3f>& ring, int k) {
  const int n = static_cast<int>(ring.size());
  std::vector<double> c(ring.size(), -1.0);
  if (k < 1 || n < 2 * k + 1) return c;
  // sum_{j != i} (x_i - x_j) over the window = (2k + 1) x_i - (window sum), the window sums from
  // prefix sums: O(n) instead of O(n k).
  std::vector<Eigen::Vector3d> prefix(ring.size() + 1);
  prefix[0].setZero();
  for (std::size_t i = 0; i < ring.size(); ++i) prefix[i + 1] = prefix[i] + ring[i].cast<double>();
  for (int i = k; i + k < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    const Eigen::Vector3d xi = ring[u].cast<double>();
    const Eigen::Vector3d sum =
        (2.0 * k + 1.0) * xi - (prefix[u + static_cast<std::size_t>(k) + 1] - prefix[u - static_cast<std::size_t>(k)]);
    const double r = xi.norm();
    if (r > 0.0) c[u] = sum.norm() / (2.0 * k * r);  // eq. 4.5
  }
  return c;
}

namespace {

// Point i is finite (with a finite time) and within [min_range_m, max_range_m].
bool usable_sweep_point(const PointCloud& sweep, std::size_t i, const FeatureParams& p) {
  const Eigen::Vector3f& q = sweep.points[i];
  if (!q.allFinite() || (sweep.has_time() && !std::isfinite(sweep.time_offsets_s[i]))) return false;
  const double r = q.norm();
  return r >= p.min_range_m && r <= p.max_range_m;
}

}  // namespace

PointCloud sanitize_sweep(const PointCloud& sweep, const FeatureParams& p) {
  if (!sweep.is_consistent()) throw Error("LOAM: sweep fields (time, ring, intensity) do not match its point count");
  PointCloud out = sweep.empty_copy();
  out.reserve(sweep.size());
  for (std::size_t i = 0; i < sweep.size(); ++i)
    if (usable_sweep_point(sweep, i, p)) out.push_back_from(sweep, i);
  return out;
}

const PointCloud& sanitized(const PointCloud& sweep, const FeatureParams& p, PointCloud& storage) {
  if (!sweep.is_consistent()) throw Error("LOAM: sweep fields (time, ring, intensity) do not match its point count");
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    if (!usable_sweep_point(sweep, i, p)) {
      storage = sanitize_sweep(sweep, p);
      return storage;
    }
  }
  return sweep;  // sanitize_sweep would keep every point, with the same fields and metadata
}

std::vector<std::uint16_t> ring_indices(const PointCloud& sweep, const FeatureParams& p) {
  if (sweep.has_ring()) return sweep.rings;
  std::vector<std::uint16_t> rings(sweep.size());
  const double span = p.max_elevation_rad - p.min_elevation_rad;
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const Eigen::Vector3f& q = sweep.points[i];
    const double elevation = std::atan2(q.z(), std::hypot(q.x(), q.y()));
    const double f = std::clamp((elevation - p.min_elevation_rad) / span, 0.0, 1.0);
    rings[i] = static_cast<std::uint16_t>(std::lround(f * (p.rings - 1)));
  }
  return rings;
}

LoamFeatures extract_features(const PointCloud& sweep, const FeatureParams& p) {
  LoamFeatures out;
  for (PointCloud* c : {&out.edges, &out.planars, &out.map_edges, &out.map_planars}) *c = sweep.empty_copy();
  if (sweep.empty()) return out;
  const std::vector<std::uint16_t> rings = ring_indices(sweep, p);
  const std::size_t n_rings = static_cast<std::size_t>(*std::max_element(rings.begin(), rings.end())) + 1;
  std::vector<std::vector<std::uint32_t>> per_ring(n_rings);
  for (std::size_t i = 0; i < sweep.size(); ++i) per_ring[rings[i]].push_back(static_cast<std::uint32_t>(i));
  std::vector<float> key(sweep.size());
  for (std::size_t i = 0; i < sweep.size(); ++i)
    key[i] = sweep.has_time() ? sweep.time_offsets_s[i] : std::atan2(sweep.points[i].y(), sweep.points[i].x());
  PointCloud with_rings;
  if (!sweep.has_ring()) {
    with_rings = sweep;
    with_rings.rings = rings;
  }
  const PointCloud& source = sweep.has_ring() ? sweep : with_rings;
  const auto earlier = [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; };
  for (auto& idx : per_ring) {
    if (!std::is_sorted(idx.begin(), idx.end(), earlier)) std::stable_sort(idx.begin(), idx.end(), earlier);
    process_ring(source, idx, p, out);
  }
  return out;
}

}  // namespace bipednav::localization
