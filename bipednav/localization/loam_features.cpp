#include "bipednav/localization/loam_features.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>

#include "bipednav/common/error.hpp"

namespace bipednav::localization {

void FeatureScratch::RingGeometry::assign(const std::vector<Eigen::Vector3f>& pts) {
  range.resize(pts.size());
  gap.assign(pts.size(), 0.0f);
  for (std::size_t i = 0; i < pts.size(); ++i) range[i] = pts[i].norm();
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) gap[i] = (pts[i + 1] - pts[i]).norm();
}

namespace {

using RingGeometry = FeatureScratch::RingGeometry;

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

// Picks up to max and max * factor points of one sub-region from `candidates` (the points past
// the threshold; indices into the ring `idx` of `sweep`) into `sharp_out` and `map_out`, best first (highest smoothness
// c for edges, lowest for planars). The selection usually runs through most candidates, so they are sorted whole, with
// their scores beside them. Candidates already picked (unreliable, or next to a selected feature) are skipped wherever
// they come, so only the others are sorted. Equal scores keep the order a chunked partial sort of `candidates` gives
// them (the order these features were selected in before; ties are rare), so that path stays for them.
//
// The sort runs on one 64-bit word per candidate: the score's bits in an order-preserving form, their
// low 16 bits replaced by the candidate's index. When no two words share their score part (so no two
// scores are equal either), their order is the scores' order, the one std::sort of the (score,
// index) pairs gives; a shared score part (a tie, or scores that differ only in the dropped bits),
// an index beyond 16 bits or a NaN falls back to the pairs (and to the tie path).
void select(std::vector<int>& candidates, const std::vector<double>& c, bool edges, const RingGeometry& ring,
            const FeatureParams& p, std::vector<char>& picked, std::vector<std::pair<double, int>>& scored,
            std::vector<std::uint64_t>& packed, const PointCloud& sweep, const std::uint32_t* idx,
            PointCloud& sharp_out, PointCloud& map_out) {
  const int max_sharp = edges ? p.max_edges_per_region : p.max_planars_per_region;
  const auto max_map = static_cast<std::size_t>(max_sharp * p.map_feature_factor);
  int sharp = 0;
  std::size_t map = 0;
  const auto consider = [&](int i) {
    if (picked[static_cast<std::size_t>(i)]) return;
    if (sharp < max_sharp) {
      sharp_out.push_back_from(sweep, idx[static_cast<std::size_t>(i)]);
      ++sharp;
    }
    map_out.push_back_from(sweep, idx[static_cast<std::size_t>(i)]);
    ++map;
    picked[static_cast<std::size_t>(i)] = 1;
    mark_neighbours(ring, i, p, picked);
  };
  constexpr std::uint64_t kIndexBits = 16, kIndexMask = (std::uint64_t{1} << kIndexBits) - 1;
  bool packable = ring.range.size() <= kIndexMask + 1;
  packed.clear();
  for (const int i : candidates) {
    if (!packable) break;
    if (picked[static_cast<std::size_t>(i)]) continue;
    const double ci = c[static_cast<std::size_t>(i)];
    const double score = (edges ? -ci : ci) + 0.0;  // -0 as +0: equal scores, equal words
    packable = score == score;
    const auto u = std::bit_cast<std::uint64_t>(score);
    const std::uint64_t key = (u >> 63) != 0 ? ~u : u | (std::uint64_t{1} << 63);  // ascending with the score
    packed.push_back((key & ~kIndexMask) | static_cast<std::uint64_t>(i));
  }
  if (packable) {
    std::sort(packed.begin(), packed.end());
    for (std::size_t n = 1; n < packed.size() && packable; ++n)
      packable = (packed[n - 1] >> kIndexBits) != (packed[n] >> kIndexBits);
  }
  if (packable) {
    for (std::size_t n = 0; n < packed.size() && map < max_map; ++n) consider(static_cast<int>(packed[n] & kIndexMask));
    return;
  }
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
    for (std::size_t n = 0; n < scored.size() && map < max_map; ++n) consider(scored[n].second);
    return;
  }
  const auto better = [&](int a, int b) {
    const double ca = c[static_cast<std::size_t>(a)], cb = c[static_cast<std::size_t>(b)];
    return edges ? ca > cb : ca < cb;
  };
  std::size_t sorted = 0;
  for (std::size_t n = 0; n < candidates.size() && map < max_map; ++n) {
    if (n == sorted) {
      const std::size_t chunk = std::min(candidates.size() - sorted, std::max<std::size_t>(2 * max_map, 16));
      const auto first = candidates.begin() + static_cast<std::ptrdiff_t>(sorted);
      const auto middle = first + static_cast<std::ptrdiff_t>(chunk);
      std::partial_sort(first, middle, candidates.end(), better);
      sorted += chunk;
    }
    consider(candidates[n]);
  }
}

// ring_smoothness into `c`, with `prefix` as its work space (both resized).
void smoothness_into(const std::vector<Eigen::Vector3f>& ring, int k, std::vector<Eigen::Vector3d>& prefix,
                     std::vector<double>& c) {
  const int n = static_cast<int>(ring.size());
  c.assign(ring.size(), -1.0);
  if (k < 1 || n < 2 * k + 1) return;
  // sum_{j != i} (x_i - x_j) over the window = (2k + 1) x_i - (window sum), the window sums from
  // prefix sums: O(n) instead of O(n k).
  prefix.resize(ring.size() + 1);
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
}

void process_ring(const PointCloud& sweep, const std::uint32_t* idx, std::size_t count, const FeatureParams& p,
                  FeatureScratch& w, LoamFeatures& out) {
  const int k = p.neighbours_per_side;
  const int n = static_cast<int>(count);
  if (n < 2 * k + 1) return;
  std::vector<Eigen::Vector3f>& pts = w.pts;
  pts.resize(count);
  for (std::size_t i = 0; i < count; ++i) pts[i] = sweep.points[idx[i]];
  smoothness_into(pts, k, w.prefix, w.c);
  const std::vector<double>& c = w.c;
  std::vector<char>& picked = w.picked;
  picked.assign(count, 0);
  w.ring.assign(pts);
  const RingGeometry& ring = w.ring;
  mark_unreliable(ring, p, picked);
  std::vector<int>&sharp = w.sharp, &flat = w.flat;
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
    select(sharp, c, true, ring, p, picked, w.scored, w.packed, sweep, idx, out.edges, out.map_edges);
    select(flat, c, false, ring, p, picked, w.scored, w.packed, sweep, idx, out.planars, out.map_planars);
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
  std::vector<Eigen::Vector3d> prefix;
  std::vector<double> c;
  smoothness_into(ring, k, prefix, c);
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

namespace {

// ring_indices of a cloud without rings, into `rings`.
void derive_rings(const PointCloud& sweep, const FeatureParams& p, std::vector<std::uint16_t>& rings) {
  rings.resize(sweep.size());
  const double span = p.max_elevation_rad - p.min_elevation_rad;
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const Eigen::Vector3f& q = sweep.points[i];
    const double elevation = std::atan2(q.z(), std::hypot(q.x(), q.y()));
    const double f = std::clamp((elevation - p.min_elevation_rad) / span, 0.0, 1.0);
    rings[i] = static_cast<std::uint16_t>(std::lround(f * (p.rings - 1)));
  }
}

}  // namespace

std::vector<std::uint16_t> ring_indices(const PointCloud& sweep, const FeatureParams& p) {
  if (sweep.has_ring()) return sweep.rings;
  std::vector<std::uint16_t> rings;
  derive_rings(sweep, p, rings);
  return rings;
}

LoamFeatures extract_features(const PointCloud& sweep, const FeatureParams& p, FeatureScratch* scratch) {
  LoamFeatures out;
  for (PointCloud* c : {&out.edges, &out.planars, &out.map_edges, &out.map_planars}) *c = sweep.empty_copy();
  if (sweep.empty()) return out;
  FeatureScratch own;
  FeatureScratch& w = scratch != nullptr ? *scratch : own;
  if (!sweep.has_ring()) derive_rings(sweep, p, w.derived_rings);
  const std::vector<std::uint16_t>& rings = sweep.has_ring() ? sweep.rings : w.derived_rings;
  const std::size_t n_rings = static_cast<std::size_t>(*std::max_element(rings.begin(), rings.end())) + 1;
  // Each ring's points in index order (a counting sort), ring after ring.
  w.ring_begin.assign(n_rings + 1, 0);
  for (const std::uint16_t r : rings) ++w.ring_begin[r + 1u];
  for (std::size_t r = 0; r < n_rings; ++r) w.ring_begin[r + 1] += w.ring_begin[r];
  w.order.resize(sweep.size());
  w.next.assign(w.ring_begin.begin(), w.ring_begin.end() - 1);
  for (std::size_t i = 0; i < sweep.size(); ++i) w.order[w.next[rings[i]]++] = static_cast<std::uint32_t>(i);
  if (!sweep.has_time()) {
    w.azimuth.resize(sweep.size());
    for (std::size_t i = 0; i < sweep.size(); ++i) w.azimuth[i] = std::atan2(sweep.points[i].y(), sweep.points[i].x());
  }
  const float* key = sweep.has_time() ? sweep.time_offsets_s.data() : w.azimuth.data();
  PointCloud with_rings;
  if (!sweep.has_ring()) {
    with_rings = sweep;
    with_rings.rings = rings;
  }
  const PointCloud& source = sweep.has_ring() ? sweep : with_rings;
  const auto earlier = [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; };
  for (std::size_t r = 0; r < n_rings; ++r) {
    const auto first = w.order.begin() + static_cast<std::ptrdiff_t>(w.ring_begin[r]);
    const auto last = w.order.begin() + static_cast<std::ptrdiff_t>(w.ring_begin[r + 1]);
    if (!std::is_sorted(first, last, earlier)) std::stable_sort(first, last, earlier);
    process_ring(source, w.order.data() + w.ring_begin[r], w.ring_begin[r + 1] - w.ring_begin[r], p, w, out);
  }
  return out;
}

}  // namespace bipednav::localization
