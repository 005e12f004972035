#include "bipednav/sim/route_clearance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/sim/footprint2d.hpp"

namespace bipednav::sim {

void RouteClearanceParams::validate() const {
  require(std::isfinite(resolution_m) && resolution_m >= 1e-3, "route_clearance.resolution_m", ">= 0.001 m");
  require(std::isfinite(height_m) && height_m > collision.ground_clearance_m, "route_clearance.height_m",
          "> collision.ground_clearance_m");
  collision.validate();
}

RouteClearanceParams RouteClearanceParams::for_robot(const RobotProfile& robot) {
  RouteClearanceParams p;
  p.height_m = robot.height_m;
  return p;
}

namespace {

constexpr double kUnbounded = std::numeric_limits<double>::infinity();

// The static footprints in square buckets, for the distance from a point to the nearest one:
// buckets are searched in rings around the point's bucket until no footprint outside the rings
// searched can be nearer than the nearest found.
class FootprintIndex {
 public:
  FootprintIndex(std::vector<Footprint2D> footprints, std::vector<std::string> names, const RouteArea& area,
                 double bucket_m)
      : footprints_(std::move(footprints)), names_(std::move(names)), min_(area.min), bucket_m_(bucket_m) {
    nx_ = std::max(1, static_cast<int>(std::ceil((area.max.x() - area.min.x()) / bucket_m)));
    ny_ = std::max(1, static_cast<int>(std::ceil((area.max.y() - area.min.y()) / bucket_m)));
    buckets_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    seen_.assign(footprints_.size(), 0);
    for (std::size_t i = 0; i < footprints_.size(); ++i) {
      const auto [x0, y0] = bucket_of(footprints_[i].bbox_min);
      const auto [x1, y1] = bucket_of(footprints_[i].bbox_max);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) buckets_[index(x, y)].push_back(static_cast<std::uint32_t>(i));
    }
  }

  // Signed distance from p to the nearest footprint (+infinity without any) and its index.
  std::pair<double, std::size_t> nearest(const Eigen::Vector2d& p) {
    ++stamp_;
    double best = kUnbounded;
    std::size_t best_i = footprints_.size();
    const auto [cx, cy] = bucket_of(p);
    const int rings = std::max({cx, cy, nx_ - 1 - cx, ny_ - 1 - cy});
    for (int k = 0; k <= rings; ++k) {
      for (int y = cy - k; y <= cy + k; ++y) {
        if (y < 0 || y >= ny_) continue;
        const int step = (y == cy - k || y == cy + k) ? 1 : 2 * k;  // the ring only
        for (int x = cx - k; x <= cx + k; x += std::max(step, 1)) {
          if (x < 0 || x >= nx_) continue;
          for (const std::uint32_t i : buckets_[index(x, y)]) {
            if (seen_[i] == stamp_) continue;
            seen_[i] = stamp_;
            const double d = signed_distance(footprints_[i], p);
            if (d < best) best = d, best_i = i;
          }
        }
      }
      // Every footprint not met yet lies outside the (2k+1)^2 buckets around p's bucket.
      if (best <= static_cast<double>(k) * bucket_m_) break;
    }
    return {best, best_i};
  }

  std::string name(std::size_t i) const { return i < names_.size() ? names_[i] : std::string(); }

 private:
  std::pair<int, int> bucket_of(const Eigen::Vector2d& p) const {
    const auto clamp_to = [](double v, int n) {
      return static_cast<int>(std::clamp(std::floor(v), 0.0, static_cast<double>(n - 1)));
    };
    return {clamp_to((p.x() - min_.x()) / bucket_m_, nx_), clamp_to((p.y() - min_.y()) / bucket_m_, ny_)};
  }
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(x);
  }

  std::vector<Footprint2D> footprints_;
  std::vector<std::string> names_;
  Eigen::Vector2d min_;
  double bucket_m_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::uint32_t>> buckets_;
  std::vector<std::uint32_t> seen_;
  std::uint32_t stamp_ = 0;
};

// The search grid: cell centres area.min + (i, j) * resolution, with their clearances computed
// when first needed.
struct RouteGrid {
  Eigen::Vector2d min;
  double res;
  int nx, ny;
  std::vector<double> clearance;  // NaN: not computed yet

  Eigen::Vector2d center(std::size_t i) const {
    const auto n = static_cast<std::size_t>(nx);
    return min + res * Eigen::Vector2d(static_cast<double>(i % n), static_cast<double>(i / n));
  }
  std::size_t cell_of(const Eigen::Vector2d& p) const {
    const auto cx = static_cast<std::size_t>(std::clamp(std::lround((p.x() - min.x()) / res), 0L, long{nx - 1}));
    const auto cy = static_cast<std::size_t>(std::clamp(std::lround((p.y() - min.y()) / res), 0L, long{ny - 1}));
    return cy * static_cast<std::size_t>(nx) + cx;
  }
  // Calls f(n, step_m) for each of cell i's 8 neighbours n inside the grid, step_m the distance
  // between the two centres.
  template <class F>
  void for_neighbours(std::size_t i, F&& f) const {
    const long x = static_cast<long>(i % static_cast<std::size_t>(nx)), y = static_cast<long>(i / nx);
    for (long dy = -1; dy <= 1; ++dy) {
      for (long dx = -1; dx <= 1; ++dx) {
        const long nxp = x + dx, nyp = y + dy;
        if ((dx == 0 && dy == 0) || nxp < 0 || nyp < 0 || nxp >= nx || nyp >= ny) continue;
        f(static_cast<std::size_t>(nyp * nx + nxp), res * ((dx != 0 && dy != 0) ? std::sqrt(2.0) : 1.0));
      }
    }
  }
  double clear(std::size_t i, FootprintIndex& index) {
    if (std::isnan(clearance[i])) clearance[i] = index.nearest(center(i)).first;
    return clearance[i];
  }
};

bool inside(const RouteArea& a, const Eigen::Vector2d& p) {
  return p.allFinite() && (p.array() >= a.min.array()).all() && (p.array() <= a.max.array()).all();
}

// The bottleneck Dijkstra: the route's value is its smallest clearance, the largest value wins.
// Returns the goal's value (0: not reached) and fills parent.
double search_widest(RouteGrid& g, FootprintIndex& index, std::size_t start, std::size_t goal,
                     std::vector<std::int64_t>& parent, std::size_t& searched) {
  std::vector<double> best(g.clearance.size(), 0.0);
  parent.assign(g.clearance.size(), -1);
  std::priority_queue<std::pair<double, std::size_t>> open;
  const double s = g.clear(start, index);
  if (!(s > 0.0)) return 0.0;
  best[start] = s;
  open.emplace(s, start);
  while (!open.empty()) {
    // Named copies, not a structured binding: the neighbour lambda captures them (clang 14).
    const double v = open.top().first;
    const std::size_t i = open.top().second;
    open.pop();
    if (v < best[i]) continue;
    ++searched;
    if (i == goal) return v;
    g.for_neighbours(i, [&](std::size_t n, double /*step_m*/) {
      const double w = std::min(v, g.clear(n, index));
      if (w > 0.0 && w > best[n]) {
        best[n] = w;
        parent[n] = static_cast<std::int64_t>(i);
        open.emplace(w, n);
      }
    });
  }
  return 0.0;
}

// Dijkstra over the cells keeping at least min_clearance_m, each step's length weighted by
// 1 + 1 m / clearance: the cell centres from start to goal (empty when the goal is not reached).
std::vector<Eigen::Vector2d> search_path(RouteGrid& g, FootprintIndex& index, std::size_t start, std::size_t goal,
                                         double min_clearance_m) {
  const double keep = min_clearance_m - 1e-9;
  std::vector<double> cost(g.clearance.size(), kUnbounded);
  std::vector<std::int64_t> parent(g.clearance.size(), -1);
  using Entry = std::pair<double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  cost[start] = 0.0;
  open.emplace(0.0, start);
  while (!open.empty()) {
    const double c = open.top().first;
    const std::size_t i = open.top().second;
    open.pop();
    if (c > cost[i]) continue;
    if (i == goal) break;
    g.for_neighbours(i, [&](std::size_t n, double step_m) {
      const double clearance = g.clear(n, index);
      if (clearance < keep) return;
      const double w = c + step_m * (1.0 + 1.0 / clearance);
      if (w < cost[n]) {
        cost[n] = w;
        parent[n] = static_cast<std::int64_t>(i);
        open.emplace(w, n);
      }
    });
  }
  std::vector<Eigen::Vector2d> path;
  if (!std::isfinite(cost[goal])) return path;
  for (std::int64_t i = static_cast<std::int64_t>(goal); i >= 0; i = parent[static_cast<std::size_t>(i)])
    path.push_back(g.center(static_cast<std::size_t>(i)));
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace

std::vector<RouteClearance> widest_routes(const World& world, const RouteArea& area, const Eigen::Vector2d& start,
                                          const std::vector<Eigen::Vector2d>& goals,
                                          const RouteClearanceParams& params) {
  params.validate();
  require(area.min.allFinite() && area.max.allFinite() && (area.max.array() > area.min.array()).all(),
          "route_clearance.area", "finite, min < max");
  std::vector<RouteClearance> out(goals.size());
  if (!inside(area, start)) return out;
  std::vector<Footprint2D> footprints;
  std::vector<std::string> names;
  for (const Geometry& g : world.statics) {
    for (Footprint2D& f : slab_footprints(g, SE3::Identity(), params.collision.ground_clearance_m, params.height_m)) {
      footprints.push_back(std::move(f));
      names.push_back(g.name);
    }
  }
  const double cells_x = std::floor((area.max.x() - area.min.x()) / params.resolution_m) + 1.0;
  const double cells_y = std::floor((area.max.y() - area.min.y()) / params.resolution_m) + 1.0;
  require(cells_x * cells_y <= 2e7, "route_clearance.resolution_m", "coarse enough for at most 2e7 cells in the area");
  RouteGrid g{area.min, params.resolution_m, static_cast<int>(cells_x), static_cast<int>(cells_y), {}};
  // Buckets no smaller than the cells: never more buckets than cells.
  FootprintIndex index(std::move(footprints), std::move(names), area, std::max(0.5, params.resolution_m));
  // One grid and one clearance cache for every goal: the searches share the cells they evaluate.
  g.clearance.assign(static_cast<std::size_t>(g.nx) * static_cast<std::size_t>(g.ny),
                     std::numeric_limits<double>::quiet_NaN());
  std::vector<std::int64_t> parent;
  const std::size_t s = g.cell_of(start);
  for (std::size_t k = 0; k < goals.size(); ++k) {
    if (!inside(area, goals[k])) continue;
    RouteClearance& r = out[k];
    const std::size_t t = g.cell_of(goals[k]);
    r.widest_m = search_widest(g, index, s, t, parent, r.cells_searched);
    r.connected = r.widest_m > 0.0;
    if (!r.connected) continue;
    // The narrowest cell of the route found.
    std::size_t narrowest = t;
    for (std::int64_t i = static_cast<std::int64_t>(t); i >= 0; i = parent[static_cast<std::size_t>(i)])
      if (g.clearance[static_cast<std::size_t>(i)] < g.clearance[narrowest]) narrowest = static_cast<std::size_t>(i);
    r.bottleneck = g.center(narrowest);
    r.bottleneck_obstacle = index.name(index.nearest(r.bottleneck).second);
    if (params.with_path) r.path = search_path(g, index, s, t, r.widest_m);
  }
  return out;
}

std::vector<Eigen::Vector2d> route_waypoints(const std::vector<Eigen::Vector2d>& path, double spacing_m) {
  require(std::isfinite(spacing_m) && spacing_m > 0.0, "route_waypoints.spacing_m", "> 0");
  std::vector<Eigen::Vector2d> out;
  if (path.empty()) return out;
  double along = 0.0;
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    along += (path[i] - path[i - 1]).norm();
    if (along >= spacing_m) {
      out.push_back(path[i]);
      along = 0.0;
    }
  }
  out.push_back(path.back());
  return out;
}

RouteClearance widest_route(const World& world, const RouteArea& area, const Eigen::Vector2d& start,
                            const Eigen::Vector2d& goal, const RouteClearanceParams& params) {
  return widest_routes(world, area, start, {goal}, params).front();
}

std::vector<RouteClearance> scenario_routes(const Scenario& scenario, const RouteClearanceParams& params) {
  const Bounds& b = scenario.bounds;
  std::vector<Eigen::Vector2d> goals;
  for (const TimedGoal& g : scenario.goals) goals.push_back(g.pose.position());
  return widest_routes(scenario.world, RouteArea{{b.min_x_m, b.min_y_m}, {b.max_x_m, b.max_y_m}},
                       scenario.start.position(), goals, params);
}

}  // namespace bipednav::sim
