// The crowd family's layouts (world_generator.hpp): corridor, doorway and hall, and their people.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "bipednav/sim/world_layouts.hpp"
#include "bipednav/sim/world_parts.hpp"

namespace bipednav::sim {
namespace {

using Vec2 = Eigen::Vector2d;
using Loop = std::vector<Vec2>;

constexpr double kPersonMinRadius_m = 0.175, kPersonMaxRadius_m = 0.25;
constexpr double kMinSpeed_mps = 0.3, kMaxSpeed_mps = 1.3;
constexpr double kKeepOffStart_m = 1.3;  // furniture keeps this far from start and goal
constexpr int kDrawsPerPerson = 40;

// The four walls of the rectangle [0, sx] x [0, sy] (centre lines on its edges).
void add_room_walls(World& w, double sx, double sy) {
  w.statics.push_back(wall_segment("wall_south", {0, 0}, {sx, 0}));
  w.statics.push_back(wall_segment("wall_north", {0, sy}, {sx, sy}));
  w.statics.push_back(wall_segment("wall_west", {0, 0}, {0, sy}));
  w.statics.push_back(wall_segment("wall_east", {sx, 0}, {sx, sy}));
}

// One piece of furniture at c: a box, a table or a pillar.
void add_furniture(World& w, Rng& rng, int index, const Vec2& c) {
  const std::string name = "furniture_" + std::to_string(index);
  const double yaw = rng.uniform(0.0, std::numbers::pi);
  const double kind = rng.uniform();
  if (kind < 0.4) {
    // Braced lists: their draws happen in order, whatever the compiler.
    w.statics.push_back(
        floor_box(name, c, yaw, Eigen::Vector3d{rng.uniform(0.5, 1.2), rng.uniform(0.4, 0.9), rng.uniform(0.5, 1.0)}));
  } else if (kind < 0.75) {
    for (Geometry& g : table(name, c, yaw, Vec2{rng.uniform(0.8, 1.6), rng.uniform(0.6, 0.9)}))
      w.statics.push_back(std::move(g));
  } else {
    w.statics.push_back(pillar(name, c, rng.uniform(0.12, 0.25), kWallHeight_m));
  }
}

// Furniture scattered in [lo, hi], kept off the start, the goal and `keep_off` (radius keep_off_m).
void scatter_furniture(LayoutDraft& d, Rng& rng, int count, const Vec2& lo, const Vec2& hi, const Vec2& keep_off,
                       double keep_off_m, int& index) {
  for (int placed = 0, tries = 0; placed < count && tries < 50 * count; ++tries) {
    const Vec2 c{rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y())};
    if ((c - d.start.position()).norm() < kKeepOffStart_m || (c - d.goal.position()).norm() < kKeepOffStart_m ||
        (c - keep_off).norm() < keep_off_m)
      continue;
    add_furniture(d.world, rng, index++, c);
    ++placed;
  }
}

// A point of the way at fraction s of its length, and the way's direction there.
std::pair<Vec2, Vec2> along_way(const LayoutDraft& d, double s) {
  double left = s * way_length(d);
  for (std::size_t i = 1; i < d.way.size(); ++i) {
    const Vec2 seg = d.way[i] - d.way[i - 1];
    if (left <= seg.norm() || i + 1 == d.way.size())
      return {d.way[i - 1] + std::min(1.0, left / std::max(seg.norm(), 1e-9)) * seg, seg.normalized()};
    left -= seg.norm();
  }
  return {d.way.front(), Vec2::UnitX()};
}

// A straight back-and-forth walk crossing the way at fraction s, at 45-135 degrees to it.
Loop crossing_walk(const LayoutDraft& d, Rng& rng, double half_length_m) {
  const auto [q, dir] = along_way(d, rng.uniform(0.2, 0.8));
  const double a = std::atan2(dir.y(), dir.x()) + rng.uniform(0.25, 0.75) * std::numbers::pi;
  const Vec2 u(std::cos(a), std::sin(a));
  return back_and_forth(q - half_length_m * u, q + half_length_m * u);
}

// Draws one person's walk until it keeps clear of the static world (its radius + 0.05 m), of start
// and goal (radius + design clearance + 0.3 m: a robot standing there is never walked into), and
// comes within radius + design clearance of the way. Adds it and returns true, or false.
bool place_person(LayoutDraft& d, const StaticClearance& statics, Rng& rng, const WorldGeneratorParams& p,
                  const std::function<Loop(Rng&, double radius)>& draw, double speed_mps) {
  for (int k = 0; k < kDrawsPerPerson; ++k) {
    const double r = rng.uniform(kPersonMinRadius_m, kPersonMaxRadius_m);
    const Loop loop = draw(rng, r);
    const double keep_off = r + p.design_clearance_m + 0.3;
    if (statics.along_loop(loop) < r + 0.05 || loop_to_polyline_distance(loop, {d.start.position()}) < keep_off ||
        loop_to_polyline_distance(loop, {d.goal.position()}) < keep_off ||
        loop_to_polyline_distance(loop, d.way) > r + p.design_clearance_m)
      continue;
    const std::string name = "person_" + std::to_string(d.world.actors.size() + 1);
    d.world.actors.push_back(person(name, r, loop, speed_mps, rng.uniform()));
    return true;
  }
  return false;
}

double walking_speed(Rng& rng) { return rng.uniform(kMinSpeed_mps, kMaxSpeed_mps); }

bool corridor_people(LayoutDraft& d, const StaticClearance& sc, Rng& rng, const WorldGeneratorParams& p) {
  const double L = d.goal.x + 0.9, half_w = 0.5 * d.feature_size.y(), xc = d.feature.x(), half_c = d.feature.y();
  const int count = static_cast<int>(rng.uniform_int(1, 4));
  for (int i = 0; i < count; ++i) {
    // The first person comes head-on or crosses; later ones may also walk slowly ahead of the robot.
    const auto kind = rng.uniform_int(0, i == 0 ? 1 : 2);
    auto lane = [&](Rng& g, double r) { return g.uniform(-half_w + r + 0.1, half_w - r - 0.1); };
    std::function<Loop(Rng&, double)> draw;
    double speed = walking_speed(rng);
    if (kind == 0) {
      draw = [&](Rng& g, double r) {
        const double y = lane(g, r);
        return back_and_forth({L - 2.2, y}, {2.2, y});
      };
    } else if (kind == 1) {
      draw = [&](Rng& g, double r) {
        const double x = xc + g.uniform(-1.0, 1.0) * std::max(0.0, half_c - r - 0.1);
        const double reach = half_w + 3.0 - r - 0.15;
        return back_and_forth({x, -reach}, {x, reach});
      };
    } else {
      speed = rng.uniform(kMinSpeed_mps, 0.6);
      draw = [&](Rng& g, double r) {
        const double y = lane(g, r);
        return back_and_forth({2.2, y}, {L - 2.2, y});
      };
    }
    if (!place_person(d, sc, rng, p, draw, speed)) return false;
  }
  return true;
}

bool doorway_people(LayoutDraft& d, const StaticClearance& sc, Rng& rng, const WorldGeneratorParams& p) {
  const Vec2 door = d.feature;
  const double a = door.x(), h = d.feature_size.y(), b = d.feature_size.x();
  const int count = static_cast<int>(rng.uniform_int(1, 3));
  for (int i = 0; i < count; ++i) {
    const auto kind = rng.uniform_int(0, i == 0 ? 1 : 2);
    std::function<Loop(Rng&, double)> draw;
    if (kind == 0) {  // through the door and back
      draw = [&](Rng& g, double) {
        const Vec2 pa{g.uniform(0.8, a - 1.5), g.uniform(0.8, h - 0.8)};
        const Vec2 pb{g.uniform(a + 1.5, a + b - 0.8), g.uniform(0.8, h - 0.8)};
        return Loop{pa, door, pb, door};
      };
    } else if (kind == 1) {  // pacing in front of the door, on either side
      draw = [&](Rng& g, double) {
        const double side = g.bernoulli(0.5) ? 1.0 : -1.0;
        const double x = a + side * g.uniform(0.7, 1.5);
        const double yc = door.y() + g.uniform(-0.5, 0.5), half = 0.5 * g.uniform(1.5, 3.0);
        return back_and_forth({x, yc - half}, {x, yc + half});
      };
    } else {  // across the way in one of the rooms
      draw = [&](Rng& g, double) { return crossing_walk(d, g, g.uniform(1.5, 2.5)); };
    }
    if (!place_person(d, sc, rng, p, draw, walking_speed(rng))) return false;
  }
  return true;
}

bool hall_people(LayoutDraft& d, const StaticClearance& sc, Rng& rng, const WorldGeneratorParams& p) {
  const int count = static_cast<int>(rng.uniform_int(2, 6));
  for (int i = 0; i < count; ++i) {
    const auto kind = rng.uniform_int(0, 2);
    std::function<Loop(Rng&, double)> draw;
    if (kind == 0) {  // straight across the hall and back
      draw = [&](Rng& g, double) { return crossing_walk(d, g, g.uniform(2.0, 4.0)); };
    } else if (kind == 1) {  // pacing across the way
      draw = [&](Rng& g, double) { return crossing_walk(d, g, g.uniform(0.75, 1.5)); };
    } else {  // looping round a point near the way
      draw = [&](Rng& g, double) {
        const auto [q, dir] = along_way(d, g.uniform(0.2, 0.8));
        const Vec2 normal(-dir.y(), dir.x());
        const double offset = g.uniform(-1.0, 1.0), radius = g.uniform(1.0, 2.0);
        return circle_loop(q + offset * normal, radius);
      };
    }
    if (!place_person(d, sc, rng, p, draw, walking_speed(rng))) return false;
  }
  return true;
}

}  // namespace

double way_length(const LayoutDraft& d) {
  double length = 0.0;
  for (std::size_t i = 1; i < d.way.size(); ++i) length += (d.way[i] - d.way[i - 1]).norm();
  return length;
}

// A corridor along x from 0 to L, W wide (y in [-W/2, W/2]), with a crossing corridor Wc wide
// centred on x = xc, open 3 m to either side. feature = (xc, Wc / 2), feature_size.y = W.
LayoutDraft draw_corridor(Rng& rng) {
  LayoutDraft d;
  d.layout = "corridor";
  const double L = rng.uniform(9.0, 13.0), W = rng.uniform(1.8, 3.0);
  const double xc = rng.uniform(0.4, 0.6) * L, Wc = rng.uniform(1.4, 2.2), arm = 3.0;
  const double t2 = 0.5 * kWallThickness_m, y = 0.5 * W + t2, xl = xc - 0.5 * Wc - t2, xr = xc + 0.5 * Wc + t2;
  const double ye = 0.5 * W + arm;
  World& w = d.world;
  for (const double s : {-1.0, 1.0}) {
    const std::string side = s < 0 ? "south" : "north";
    w.statics.push_back(wall_segment("wall_" + side + "_1", {0, s * y}, {xl, s * y}));
    w.statics.push_back(wall_segment("wall_" + side + "_2", {xr, s * y}, {L, s * y}));
    w.statics.push_back(wall_segment("wall_" + side + "_3", {xl, s * y}, {xl, s * ye}));
    w.statics.push_back(wall_segment("wall_" + side + "_4", {xr, s * y}, {xr, s * ye}));
    w.statics.push_back(wall_segment("wall_" + side + "_5", {xl, s * ye}, {xr, s * ye}));
  }
  w.statics.push_back(wall_segment("wall_west", {0, -y}, {0, y}));
  w.statics.push_back(wall_segment("wall_east", {L, -y}, {L, y}));
  d.start = Pose2{0.9, rng.uniform(-0.2, 0.2), 0.0};
  d.goal = Pose2{L - 0.9, rng.uniform(-0.2, 0.2), 0.0};
  // Benches against the walls, away from the ends and the crossing.
  const int benches = static_cast<int>(rng.uniform_int(0, 2));
  for (int i = 0; i < benches; ++i) {
    double x = rng.uniform(1.8, L - 1.8);
    if (std::abs(x - xc) < 0.5 * Wc + 0.8) continue;
    const double depth = rng.uniform(0.3, 0.45), side = rng.bernoulli(0.5) ? 1.0 : -1.0;
    w.statics.push_back(floor_box("bench_" + std::to_string(i + 1), {x, side * (0.5 * W - 0.5 * depth)}, 0.0,
                                  Eigen::Vector3d{rng.uniform(0.8, 1.5), depth, 0.45}));
  }
  d.way = {d.start.position(), d.goal.position()};
  d.feature = Vec2(xc, 0.5 * Wc);
  d.feature_size = Vec2(Wc, W);
  return d;
}

// Rooms A (x in [0, a]) and B (x in [a, a + b]), y in [0, h], joined by a door D wide centred on
// (a, yd). feature = the door's centre, feature_size = (b, h).
LayoutDraft draw_doorway(Rng& rng) {
  LayoutDraft d;
  d.layout = "doorway";
  const double a = rng.uniform(4.5, 6.5), b = rng.uniform(4.5, 6.5), h = rng.uniform(4.5, 7.0);
  const double D = rng.uniform(1.1, 1.6), yd = rng.uniform(1.2, h - 1.2), t2 = 0.5 * kWallThickness_m;
  add_room_walls(d.world, a + b, h);
  d.world.statics.push_back(wall_segment("wall_door_1", {a, 0}, {a, yd - 0.5 * D - t2}));
  d.world.statics.push_back(wall_segment("wall_door_2", {a, yd + 0.5 * D + t2}, {a, h}));
  d.start = Pose2{rng.uniform(0.9, a - 1.8), rng.uniform(0.9, h - 0.9), 0.0};
  d.goal = Pose2{rng.uniform(a + 1.8, a + b - 0.9), rng.uniform(0.9, h - 0.9), 0.0};
  const Vec2 door(a, yd);
  int index = 1;
  scatter_furniture(d, rng, static_cast<int>(rng.uniform_int(1, 3)), {0.5, 0.5}, {a - 0.5, h - 0.5}, door, 1.6, index);
  scatter_furniture(d, rng, static_cast<int>(rng.uniform_int(1, 3)), {a + 0.5, 0.5}, {a + b - 0.5, h - 0.5}, door, 1.6,
                    index);
  d.way = {d.start.position(), door, d.goal.position()};
  d.feature = door;
  d.feature_size = Vec2(b, h);
  return d;
}

// An open hall [0, wx] x [0, wy] with 3-8 pieces of furniture; start and goal at its ends.
LayoutDraft draw_hall(Rng& rng) {
  LayoutDraft d;
  d.layout = "hall";
  const double wx = rng.uniform(9.0, 13.0), wy = rng.uniform(7.0, 10.0);
  add_room_walls(d.world, wx, wy);
  d.start = Pose2{1.0, rng.uniform(1.5, wy - 1.5), 0.0};
  d.goal = Pose2{wx - 1.0, rng.uniform(1.5, wy - 1.5), 0.0};
  int index = 1;
  scatter_furniture(d, rng, static_cast<int>(rng.uniform_int(3, 8)), {0.6, 0.6}, {wx - 0.6, wy - 0.6},
                    d.start.position(), 0.0, index);
  d.way = {d.start.position(), d.goal.position()};
  return d;
}

bool add_people(LayoutDraft& d, Rng& rng, const WorldGeneratorParams& p) {
  const StaticClearance statics(d.world, kPersonHeight_m);
  if (d.layout == "corridor") return corridor_people(d, statics, rng, p);
  if (d.layout == "doorway") return doorway_people(d, statics, rng, p);
  return hall_people(d, statics, rng, p);
}

}  // namespace bipednav::sim
