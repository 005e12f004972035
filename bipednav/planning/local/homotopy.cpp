#include "bipednav/planning/local/homotopy.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <queue>

#include "bipednav/common/angles.hpp"

namespace bipednav::planning::local {

namespace {

double orient(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

bool segments_intersect(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                        const Eigen::Vector2d& d) {
  const double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a), o4 = orient(c, d, b);
  return ((o1 > 0) != (o2 > 0)) && ((o3 > 0) != (o4 > 0));
}

std::vector<Eigen::Vector2d> band_polyline(const TebBand& band) {
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(band.size());
  for (const auto& p : band.poses) pts.push_back(p.position());
  return pts;
}

// Free when the segment keeps min_dist from every obstacle, or at least does not come closer to
// it than its end points already are (the robot may start inside the margin).
bool edge_free(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::vector<Obstacle>& obstacles,
               double min_dist) {
  for (const auto& o : obstacles) {
    if (distance_to_segment(o.centroid.x(), o.centroid.y(), a, b) - o.radius_m > min_dist) continue;
    const double need = std::min({min_dist, obstacle_distance(o, a.x(), a.y()), obstacle_distance(o, b.x(), b.y())});
    if (segment_obstacle_distance(a, b, o) < need - 1e-9) return false;
  }
  return true;
}

// One segment's share of the winding signature: the signed angle from p - c to q - c.
double winding_term(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& c) {
  const Eigen::Vector2d a = p - c, b = q - c;
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}

struct Partial {
  double length;
  std::vector<int> nodes;
  bool operator>(const Partial& o) const { return length > o.length || (length == o.length && nodes > o.nodes); }
};

}  // namespace

std::vector<double> winding_signature(const std::vector<Eigen::Vector2d>& path,
                                      const std::vector<Eigen::Vector2d>& centroids) {
  std::vector<double> sig(centroids.size(), 0.0);
  for (std::size_t l = 0; l < centroids.size(); ++l) {
    for (std::size_t i = 1; i < path.size(); ++i) sig[l] += winding_term(path[i - 1], path[i], centroids[l]);
  }
  return sig;
}

bool same_homotopy_class(const std::vector<double>& a, const std::vector<double>& b, double tolerance_rad) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::abs(a[i] - b[i]) > tolerance_rad) return false;
  }
  return true;
}

double segment_obstacle_distance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Obstacle& o) {
  const auto& v = o.vertices;
  double d = std::min(obstacle_distance(o, a.x(), a.y()), obstacle_distance(o, b.x(), b.y()));
  if (d <= 0.0) return 0.0;
  for (const auto& p : v) d = std::min(d, distance_to_segment(p.x(), p.y(), a, b));
  if (v.size() >= 2) {
    const std::size_t edges = v.size() == 2 ? 1 : v.size();
    for (std::size_t i = 0; i < edges; ++i) {
      if (segments_intersect(a, b, v[i], v[(i + 1) % v.size()])) return 0.0;
    }
  }
  return d;
}

namespace {

// The sparse roadmap: start (node 0), keypoints left and right of the obstacles nearest to the
// start-goal line, goal (last node); edges only advance along the line and keep the clearance.
struct Roadmap {
  std::vector<Eigen::Vector2d> nodes;
  std::vector<std::vector<int>> adj;
};

Roadmap build_roadmap(const Eigen::Vector2d& s, const Eigen::Vector2d& g, const std::vector<Obstacle>& obstacles,
                      double min_dist_m, const HomotopyParams& params) {
  const double len = (g - s).norm();
  const Eigen::Vector2d dir = (g - s) / len, nrm(-dir.y(), dir.x());
  std::vector<std::pair<double, std::size_t>> near;  // nearest to the line first
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    const Eigen::Vector2d r = obstacles[i].centroid - s;
    const double t = r.dot(dir), lat = std::abs(r.dot(nrm)) - obstacles[i].radius_m;
    if (t > 0.0 && t < len && lat < params.corridor_halfwidth_m) near.emplace_back(lat, i);
  }
  std::sort(near.begin(), near.end());
  if (static_cast<int>(near.size()) > params.max_keypoint_obstacles) near.resize(params.max_keypoint_obstacles);
  const double clearance = params.roadmap_clearance_ratio * min_dist_m;
  Roadmap rm;
  rm.nodes.push_back(s);
  for (const auto& [lat, i] : near) {
    const Obstacle& o = obstacles[i];
    for (const double side : {1.0, -1.0}) {
      const Eigen::Vector2d p = o.centroid + side * (o.radius_m + min_dist_m + params.keypoint_margin_m) * nrm;
      const double t = (p - s).dot(dir);
      bool free = t > 0.0 && t < len;
      for (std::size_t j = 0; free && j < obstacles.size(); ++j)
        free = obstacle_distance(obstacles[j], p.x(), p.y()) > clearance;
      if (free) rm.nodes.push_back(p);
    }
  }
  rm.nodes.push_back(g);
  const int n = static_cast<int>(rm.nodes.size());
  rm.adj.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double ti = (rm.nodes[i] - s).dot(dir);
    for (int j = 1; j < n; ++j) {
      if ((rm.nodes[j] - s).dot(dir) > ti + 1e-6 && edge_free(rm.nodes[i], rm.nodes[j], obstacles, clearance))
        rm.adj[i].push_back(j);
    }
  }
  return rm;
}

}  // namespace

std::vector<std::vector<Eigen::Vector2d>> candidate_paths(const Pose2& start, const Pose2& goal,
                                                          const std::vector<Obstacle>& obstacles,
                                                          const std::vector<Eigen::Vector2d>& centroids,
                                                          double min_dist_m,
                                                          const std::vector<std::vector<double>>& known, int max_new,
                                                          const HomotopyParams& params) {
  std::vector<std::vector<Eigen::Vector2d>> out;
  if ((goal.position() - start.position()).norm() < 1e-6 || max_new <= 0) return out;
  const Roadmap rm = build_roadmap(start.position(), goal.position(), obstacles, min_dist_m, params);
  const int goal_node = static_cast<int>(rm.nodes.size()) - 1;
  // The winding signature of a roadmap path, from its edges' terms (computed once per edge: the enumerated
  // paths share edges). Each centroid's terms are summed in path order, as winding_signature does.
  const std::size_t nn = rm.nodes.size();
  std::vector<std::vector<double>> edge_terms(nn * nn);
  const auto signature = [&](const std::vector<int>& nodes) {
    std::vector<double> sig(centroids.size(), 0.0);
    for (std::size_t i = 1; i < nodes.size(); ++i) {
      const auto u = static_cast<std::size_t>(nodes[i - 1]), v = static_cast<std::size_t>(nodes[i]);
      std::vector<double>& t = edge_terms[u * nn + v];
      if (t.size() != centroids.size()) {
        t.resize(centroids.size());
        for (std::size_t l = 0; l < centroids.size(); ++l) t[l] = winding_term(rm.nodes[u], rm.nodes[v], centroids[l]);
      }
      for (std::size_t l = 0; l < centroids.size(); ++l) sig[l] += t[l];
    }
    return sig;
  };
  // Best-first enumeration of paths in order of length (k shortest paths in a DAG).
  std::vector<std::vector<double>> seen = known;
  std::priority_queue<Partial, std::vector<Partial>, std::greater<>> open;
  open.push({0.0, {0}});
  for (int pops = 0; !open.empty() && pops < params.max_path_expansions; ++pops) {
    Partial p = open.top();
    open.pop();
    if (p.nodes.back() == goal_node) {
      auto sig = signature(p.nodes);
      if (std::none_of(seen.begin(), seen.end(),
                       [&](const auto& k) { return same_homotopy_class(k, sig, params.signature_tolerance_rad); })) {
        seen.push_back(std::move(sig));
        std::vector<Eigen::Vector2d> path;
        for (int k : p.nodes) path.push_back(rm.nodes[k]);
        out.push_back(std::move(path));
        if (static_cast<int>(out.size()) >= max_new) break;
      }
      continue;
    }
    for (int j : rm.adj[p.nodes.back()]) {
      Partial q{p.length + (rm.nodes[j] - rm.nodes[p.nodes.back()]).norm(), p.nodes};
      q.nodes.push_back(j);
      open.push(std::move(q));
    }
  }
  return out;
}

HomotopyPlanner::HomotopyPlanner(const TebParams& params) : params_(params), pool_(params.homotopy.num_threads) {
  params_.validate();
}

void HomotopyPlanner::reset() {
  bands_.clear();
  selected_id_ = 0;
}

void HomotopyPlanner::warm_start(const Pose2& start, const Pose2& goal, const std::vector<Eigen::Vector2d>& centroids,
                                 std::vector<std::vector<double>>& signatures) {
  std::erase_if(bands_, [&](BandCandidate& b) { return !warm_start_band(b.band, start, goal, params_.band); });
  // The selected band first, so it survives when another band fell into its class.
  std::stable_partition(bands_.begin(), bands_.end(), [&](const BandCandidate& b) { return b.id == selected_id_; });
  drop_duplicates(centroids, false, &signatures);
}

void HomotopyPlanner::drop_duplicates(const std::vector<Eigen::Vector2d>& centroids, bool by_cost,
                                      std::vector<std::vector<double>>* kept) {
  if (kept) kept->clear();
  if (bands_.size() < 2) return;  // nothing to compare: every band stays, in its order
  std::vector<std::size_t> order(bands_.size());
  std::iota(order.begin(), order.end(), 0);
  if (by_cost) {
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return bands_[a].cost.selection() < bands_[b].cost.selection();
    });
  }
  std::vector<std::vector<double>> kept_sig;
  std::vector<bool> keep(bands_.size(), false);
  for (const std::size_t i : order) {
    auto sig = winding_signature(band_polyline(bands_[i].band), centroids);
    const double tol = params_.homotopy.signature_tolerance_rad;
    if (std::none_of(kept_sig.begin(), kept_sig.end(),
                     [&](const auto& k) { return same_homotopy_class(k, sig, tol); })) {
      kept_sig.push_back(std::move(sig));
      keep[i] = true;
    }
  }
  std::vector<BandCandidate> out;
  for (std::size_t i = 0; i < bands_.size(); ++i) {
    if (keep[i]) out.push_back(std::move(bands_[i]));
  }
  bands_ = std::move(out);
  if (kept && !by_cost) *kept = std::move(kept_sig);  // in band order: `order` is the identity
}

void HomotopyPlanner::add_candidates(const Pose2& start, const Pose2& goal, const std::vector<Eigen::Vector2d>& via,
                                     const std::vector<Obstacle>& obstacles,
                                     const std::vector<Eigen::Vector2d>& centroids,
                                     std::vector<std::vector<double>>* signatures) {
  if (bands_.empty())
    bands_.push_back({next_id_++, init_band(start, via, goal, params_.limits, params_.band), {}, false});
  if (!params_.homotopy.enabled) return;
  const int free_slots = params_.homotopy.max_classes - static_cast<int>(bands_.size());
  if (free_slots <= 0) return;
  std::vector<std::vector<double>> known;
  if (signatures != nullptr && !signatures->empty() && signatures->size() == bands_.size())
    known = std::move(*signatures);  // warm_start's, of these bands and centroids
  else
    for (const auto& b : bands_) known.push_back(winding_signature(band_polyline(b.band), centroids));
  for (const auto& path : candidate_paths(start, goal, obstacles, centroids, params_.limits.min_obstacle_dist_m, known,
                                          free_slots, params_.homotopy)) {
    const std::vector<Eigen::Vector2d> inner(path.begin() + 1, path.end() - 1);
    bands_.push_back({next_id_++, init_band(start, inner, goal, params_.limits, params_.band), {}, false});
  }
}

void HomotopyPlanner::optimise_all(const Twist& v0, const std::vector<Eigen::Vector2d>& via,
                                   const std::vector<Obstacle>& obstacles) {
  TebProblemInput input;
  input.obstacles = &obstacles;
  input.via_points = via;
  input.start_velocity = v0;
  input.moving = &moving_;
  pool_.parallel_for(bands_.size(), [&](std::size_t i) {
    BandCandidate& b = bands_[i];
    b.ok = optimize_band(b.band, input, params_.limits, params_.band, params_.optim);
    b.cost = evaluate_band(b.band, input, params_.limits, params_.optim);
  });
}

const BandCandidate* HomotopyPlanner::select() {
  const BandCandidate* best = nullptr;
  double best_cost = 0.0;
  for (const auto& b : bands_) {
    const double c = b.cost.selection() * (b.id == selected_id_ ? params_.homotopy.selection_hysteresis : 1.0);
    if (best == nullptr || c < best_cost) best = &b, best_cost = c;
  }
  if (best == nullptr) {
    selected_id_ = 0;
    return nullptr;
  }
  selected_id_ = best->id;
  // Bands far worse than the best only cost time; their slots go to fresh candidates.
  const double limit = params_.homotopy.max_cost_ratio * best->cost.selection();
  std::erase_if(bands_, [&](const BandCandidate& b) { return b.id != selected_id_ && b.cost.selection() > limit; });
  for (const auto& b : bands_) {
    if (b.id == selected_id_) return &b;
  }
  return nullptr;
}

const BandCandidate* HomotopyPlanner::plan(const Pose2& start, const Pose2& goal, const Twist& start_velocity,
                                           const std::vector<Eigen::Vector2d>& via_points,
                                           const std::vector<Obstacle>& obstacles) {
  // Only obstacles near the start-goal corridor can tell the candidates apart.
  std::vector<Eigen::Vector2d> centroids;
  const double reach = params_.homotopy.corridor_halfwidth_m;
  for (const auto& o : obstacles) {
    if (distance_to_segment(o.centroid.x(), o.centroid.y(), start.position(), goal.position()) - o.radius_m < reach)
      centroids.push_back(o.centroid);
  }
  std::vector<std::vector<double>> signatures;
  warm_start(start, goal, centroids, signatures);
  add_candidates(start, goal, via_points, obstacles, centroids, &signatures);
  optimise_all(start_velocity, via_points, obstacles);
  std::erase_if(bands_, [](const BandCandidate& b) { return !b.ok; });
  drop_duplicates(centroids, true);
  return select();
}

}  // namespace bipednav::planning::local
