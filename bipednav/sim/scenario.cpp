#include "bipednav/sim/scenario.hpp"

#include <algorithm>
#include <cmath>

#include "bipednav/io/param_reader.hpp"
#include "bipednav/sim/sdf_world.hpp"
#include "bipednav/sim/world_drawing.hpp"

namespace bipednav::sim {
namespace fs = std::filesystem;
namespace {

constexpr double kBoundsMargin_m = 0.5;

// A list of `n` finite numbers (n = 0: any length >= 1). Returns false when the key is absent.
bool read_numbers(io::ParamReader& r, const std::string& key, std::size_t n, std::vector<double>& out,
                  const std::string& expected) {
  if (!r.get(key, out)) return false;
  const bool ok = (n == 0 ? !out.empty() : out.size() == n) &&
                  std::all_of(out.begin(), out.end(), [](double v) { return std::isfinite(v); });
  if (!ok) r.fail(key, expected);
  return true;
}

Pose2 read_pose(io::ParamReader& r, const std::string& key) {
  std::vector<double> v;
  if (!read_numbers(r, key, 3, v, "[x, y, yaw] (3 finite numbers: m, m, rad)"))
    r.fail(key, "[x, y, yaw] to be present");
  return {v[0], v[1], v[2]};
}

double read_positive(io::ParamReader& r, const std::string& key, double value) {
  r.get(key, value);
  if (!(value > 0.0 && std::isfinite(value))) r.fail(key, "a finite number > 0");
  return value;
}

Geometry standing_box(const std::string& name, const Pose2& pose, const Eigen::Vector3d& size) {
  return {name, make_se3(pose.x, pose.y, 0.5 * size.z(), 0, 0, pose.theta), Box{size}};
}

void read_walls(io::ParamReader& w, World& world) {
  const double thickness = read_positive(w, "wall_thickness_m", 0.2);
  const double height = read_positive(w, "wall_height_m", 2.0);
  int i = 0;
  for (io::ParamReader& r : w.children("walls")) {
    std::vector<double> a, b;
    if (!read_numbers(r, "from", 2, a, "[x, y] (2 finite numbers)")) r.fail("from", "[x, y] to be present");
    if (!read_numbers(r, "to", 2, b, "[x, y] (2 finite numbers)")) r.fail("to", "[x, y] to be present");
    const double t = read_positive(r, "thickness_m", thickness), h = read_positive(r, "height_m", height);
    r.finish();
    const Eigen::Vector2d d(b[0] - a[0], b[1] - a[1]);
    // Each wall runs half a thickness past its end points, so walls meeting at a corner close it.
    const Pose2 centre{0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), std::atan2(d.y(), d.x())};
    world.statics.push_back(standing_box("wall_" + std::to_string(i++), centre, {d.norm() + t, t, h}));
  }
}

void read_static_obstacles(io::ParamReader& w, World& world) {
  int i = 0;
  for (io::ParamReader& r : w.children("boxes")) {
    std::string name = "box_" + std::to_string(i++);
    r.get("name", name);
    const Pose2 pose = read_pose(r, "pose");
    std::vector<double> s;
    if (!read_numbers(r, "size_m", 3, s, "[sx, sy, sz] (3 numbers > 0)") || s[0] <= 0 || s[1] <= 0 || s[2] <= 0)
      r.fail("size_m", "[sx, sy, sz] (3 numbers > 0)");
    r.finish();
    world.statics.push_back(standing_box(name, pose, {s[0], s[1], s[2]}));
  }
  i = 0;
  for (io::ParamReader& r : w.children("cylinders")) {
    std::string name = "cylinder_" + std::to_string(i++);
    r.get("name", name);
    std::vector<double> p;
    if (!read_numbers(r, "position", 2, p, "[x, y] (2 finite numbers)")) r.fail("position", "[x, y] to be present");
    const double radius = read_positive(r, "radius_m", 0.15), height = read_positive(r, "height_m", 2.0);
    r.finish();
    world.statics.push_back({name, make_se3(p[0], p[1], 0.5 * height, 0, 0, 0), Cylinder{radius, height}});
  }
}

// The trajectory of a moving obstacle: explicit [t, x, y, yaw] waypoints, or a path walked at
// a constant speed (closed back to its start when looping).
void read_trajectory(io::ParamReader& r, Actor& a) {
  const auto finite = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  std::vector<std::vector<double>> rows;
  if (r.get("waypoints", rows)) {
    const std::string expected = "a non-empty list of [t, x, y, yaw] (finite numbers, t non-decreasing)";
    if (rows.empty()) r.fail("waypoints", expected);
    for (const auto& v : rows) {
      if (v.size() != 4 || !finite(v) || (!a.trajectory.empty() && v[0] < a.trajectory.back().time_s))
        r.fail("waypoints", expected);
      a.trajectory.push_back({v[0], make_se3(v[1], v[2], 0, 0, 0, v[3])});
    }
    return;
  }
  const double speed = read_positive(r, "speed_mps", 0.3);
  if (!r.get("path", rows) || rows.empty()) r.fail("path", "either 'path' (with 'speed_mps') or 'waypoints'");
  std::vector<Eigen::Vector2d> path;
  for (const auto& v : rows) {
    if (v.size() != 2 || !finite(v)) r.fail("path", "a list of [x, y] (finite numbers)");
    path.emplace_back(v[0], v[1]);
  }
  if (a.loop && path.size() > 1) path.push_back(path.front());
  double t = 0.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    if (i > 0) t += (path[i] - path[i - 1]).norm() / speed;
    a.trajectory.push_back({t, make_se3(path[i].x(), path[i].y(), 0, 0, 0, 0)});
  }
}

void read_moving(io::ParamReader& w, World& world) {
  int i = 0;
  for (io::ParamReader& r : w.children("moving")) {
    Actor a;
    a.name = "moving_" + std::to_string(i++);
    r.get("name", a.name);
    std::string shape = "box";
    r.get("shape", shape);
    if (shape == "box") {
      std::vector<double> s{0.5, 0.5, 0.5};
      read_numbers(r, "size_m", 3, s, "[sx, sy, sz] (3 numbers > 0)");
      if (s[0] <= 0 || s[1] <= 0 || s[2] <= 0) r.fail("size_m", "[sx, sy, sz] (3 numbers > 0)");
      a.parts.push_back(standing_box("body", Pose2{}, {s[0], s[1], s[2]}));
    } else if (shape == "cylinder") {
      const double radius = read_positive(r, "radius_m", 0.25), height = read_positive(r, "height_m", 1.7);
      a.parts.push_back({"body", make_se3(0, 0, 0.5 * height, 0, 0, 0), Cylinder{radius, height}});
    } else {
      r.fail("shape", "box or cylinder");
    }
    r.get("loop", a.loop);
    r.get("delay_s", a.delay_s);
    if (!(a.delay_s >= 0.0)) r.fail("delay_s", "a number >= 0");
    read_trajectory(r, a);
    r.finish();
    world.actors.push_back(std::move(a));
  }
}

void read_inline_world(io::ParamReader w, World& world) {
  w.get("name", world.name);
  bool ground = true;
  w.get("ground_plane", ground);
  const bool has_ground = std::any_of(world.statics.begin(), world.statics.end(),
                                      [](const Geometry& g) { return std::holds_alternative<Plane>(g.shape); });
  if (ground && !has_ground) world.statics.push_back({"ground_plane", SE3::Identity(), Plane{}});
  read_walls(w, world);
  read_static_obstacles(w, world);
  read_moving(w, world);
  w.finish();
}

void read_goals_and_commands(io::ParamReader& r, Scenario& s) {
  for (io::ParamReader& g : r.children("goals")) {
    TimedGoal goal;
    g.get("time_s", goal.time_s);
    if (!(goal.time_s >= 0.0) || (!s.goals.empty() && goal.time_s < s.goals.back().time_s))
      g.fail("time_s", "a time >= 0, not before the previous goal's");
    goal.pose = read_pose(g, "pose");
    g.finish();
    s.goals.push_back(goal);
  }
  for (io::ParamReader& c : r.children("commands")) {
    ScriptedCommand cmd;
    c.get("time_s", cmd.time_s);
    if (!(cmd.time_s >= 0.0) || (!s.commands.empty() && cmd.time_s < s.commands.back().time_s))
      c.fail("time_s", "a time >= 0, not before the previous command's");
    c.get("linear_x", cmd.twist.linear_x);
    c.get("linear_y", cmd.twist.linear_y);
    c.get("angular_z", cmd.twist.angular_z);
    if (!cmd.twist.is_finite()) c.fail("linear_x", "finite velocities");
    c.finish();
    s.commands.push_back(cmd);
  }
  for (io::ParamReader& f : r.children("faults")) s.faults.push_back(read_fault(f));
}

Bounds compute_bounds(io::ParamReader& r, const Scenario& s) {
  std::vector<double> v;
  if (read_numbers(r, "bounds", 4, v, "[min_x, min_y, max_x, max_y] (finite, min < max)")) {
    if (!(v[0] < v[2] && v[1] < v[3])) r.fail("bounds", "[min_x, min_y, max_x, max_y] with min < max");
    return {v[0], v[1], v[2], v[3]};
  }
  Bounds2 b = world_bounds(s.world);
  b.add(s.start.position());
  for (const TimedGoal& g : s.goals) b.add(g.pose.position());
  b = b.inflated(kBoundsMargin_m);
  return {b.min_x_m, b.min_y_m, b.max_x_m, b.max_y_m};
}

}  // namespace

void Scenario::validate() const {
  require(!name.empty(), "name", "a non-empty scenario name");
  require(!robot.empty(), "robot", "a robot profile name");
  require(start.is_finite(), "start", "a finite pose");
  require(!goals.empty(), "goals", "at least one goal");
  for (std::size_t i = 0; i < goals.size(); ++i) {
    require(goals[i].pose.is_finite(), "goals[" + std::to_string(i) + "].pose", "a finite pose");
    require(goals[i].time_s >= 0.0 && goals[i].time_s < time_limit_s, "goals[" + std::to_string(i) + "].time_s",
            "in [0, time_limit_s)");
  }
  require(time_limit_s > 0.0 && std::isfinite(time_limit_s), "time_limit_s", "a finite number > 0");
  require(goal_tolerance_m > 0.0, "goal_tolerance_m", "> 0");
  require(goal_tolerance_rad > 0.0, "goal_tolerance_rad", "> 0");
  require(bounds.max_x_m > bounds.min_x_m && bounds.max_y_m > bounds.min_y_m, "bounds", "min < max");
  require(bounds.contains(start.x, start.y), "start", "inside the bounds");
  for (std::size_t i = 0; i < goals.size(); ++i)
    require(bounds.contains(goals[i].pose.x, goals[i].pose.y), "goals[" + std::to_string(i) + "].pose",
            "inside the bounds");
  for (const Fault& f : faults) f.validate();
}

const TimedGoal* Scenario::goal_at(double t_s) const {
  const TimedGoal* current = nullptr;
  for (const TimedGoal& g : goals)
    if (g.time_s <= t_s) current = &g;
  return current;
}

Twist Scenario::command_at(double t_s) const {
  Twist current;
  for (const ScriptedCommand& c : commands)
    if (c.time_s <= t_s) current = c.twist;
  return current;
}

Scenario load_scenario(const fs::path& file, const std::vector<fs::path>& model_paths) {
  io::ParamReader r = io::ParamReader::from_file(file);
  const fs::path dir = file.parent_path();
  Scenario s;
  s.name = file.stem().string();
  r.get("name", s.name);
  r.get("description", s.description);
  r.get("robot", s.robot);
  std::vector<std::string> extra_paths;
  r.get("model_paths", extra_paths);
  std::vector<fs::path> paths;
  for (const std::string& p : extra_paths) paths.push_back(dir / p);
  paths.insert(paths.end(), model_paths.begin(), model_paths.end());
  std::string world_file;
  if (r.get("world_file", world_file)) {
    try {
      s.world = load_sdf_world(dir / world_file, paths);
    } catch (const FileError& e) {
      throw FileError(file.string(), "world_file", e.what());
    }
  }
  if (r.has("world")) read_inline_world(r.child("world"), s.world);
  if (world_file.empty() && !r.has("world")) r.fail("world", "an inline 'world' or a 'world_file'");
  if (s.world.name.empty()) s.world.name = s.name;
  s.start = read_pose(r, "start");
  read_goals_and_commands(r, s);
  r.get("time_limit_s", s.time_limit_s);
  r.get("seed", s.seed);
  r.get("goal_tolerance_m", s.goal_tolerance_m);
  r.get("goal_tolerance_rad", s.goal_tolerance_rad);
  s.bounds = compute_bounds(r, s);
  r.finish();
  try {
    s.validate();
  } catch (const ParamError& e) {
    throw FileError(file.string(), "", e.what());
  }
  return s;
}

}  // namespace bipednav::sim
