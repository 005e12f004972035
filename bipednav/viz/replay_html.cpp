#include "bipednav/viz/replay_html.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <tuple>

#include "bipednav/common/error.hpp"
#include "bipednav/viz/byte_codec.hpp"
#include "bipednav/viz/replay_template.hpp"  // generated: kReplayTemplate

namespace bipednav::viz {

namespace {

using nlohmann::json;

constexpr std::string_view kPlaceholder = "{{REPLAY_DATA}}";

// Rounds to a power-of-ten step so the JSON prints short decimals (1.23, not 1.2300000000000002).
class Rounder {
 public:
  explicit Rounder(double resolution_m) : scale_(std::pow(10.0, std::ceil(-std::log10(resolution_m) - 1e-9))) {}
  double operator()(double v) const { return std::round(v * scale_) / scale_; }
  double scale() const { return scale_; }

 private:
  double scale_;
};

double round_angle(double rad) { return std::round(rad * 1000.0) / 1000.0; }

json pose_json(const Pose2& p, const Rounder& r) { return json::array({r(p.x), r(p.y), round_angle(p.theta)}); }

json path_json(const Path& path, const Rounder& r) {
  json xy = json::array();
  for (const auto& p : path.poses) {
    xy.push_back(r(p.x));
    xy.push_back(r(p.y));
  }
  return xy;
}

json outline_json(const Outline& outline, const Rounder& r) {
  json xy = json::array();
  for (const auto& p : outline) {
    xy.push_back(r(p.x()));
    xy.push_back(r(p.y()));
  }
  return xy;
}

// Points as little-endian int16 pairs in units of the rounder's step; points out of range are dropped.
std::string points_packed(const std::vector<Eigen::Vector2f>& points, const Rounder& r) {
  std::vector<std::uint8_t> bytes;
  bytes.reserve(points.size() * 4);
  constexpr double kMax = std::numeric_limits<std::int16_t>::max();
  for (const auto& p : points) {
    const double qx = std::round(p.x() * r.scale()), qy = std::round(p.y() * r.scale());
    if (!(std::abs(qx) <= kMax && std::abs(qy) <= kMax)) continue;  // also drops NaN
    for (const double q : {qx, qy}) {
      const auto u = static_cast<std::uint16_t>(static_cast<std::int16_t>(q));
      bytes.push_back(static_cast<std::uint8_t>(u & 0xff));
      bytes.push_back(static_cast<std::uint8_t>(u >> 8));
    }
  }
  return pack_bytes(bytes);
}

json grids_json(const std::vector<ReplayGrid>& grids) {
  json out = json::array();
  for (const auto& g : grids) {
    require(g.width >= 0 && g.height >= 0 && g.cells.size() == static_cast<std::size_t>(g.width) * g.height,
            "ReplayGrid.cells", "width * height cost bytes");
    out.push_back({{"t", g.t_s},
                   {"w", g.width},
                   {"h", g.height},
                   {"res", g.resolution_m},
                   {"ox", g.origin_x_m},
                   {"oy", g.origin_y_m},
                   {"cells", pack_bytes(g.cells)}});
  }
  return out;
}

json summary_json(const ReplaySummary& s, const Rounder& r) {
  return {{"scenario", s.scenario},
          {"robot", s.robot},
          {"success", s.success},
          {"outcome", s.outcome},
          {"message", s.message},
          {"time_s", r(s.time_s)},
          {"path_length_m", r(s.path_length_m)},
          {"min_clearance_m", r(s.min_clearance_m)},
          {"collisions", s.collisions},
          {"replans", s.replans},
          {"recoveries", s.recoveries}};
}

// A foot as [left (1) / right (0), x, y, yaw, action kind].
json foot_json(const ReplayFoot& f, const Rounder& r) {
  return json::array({f.left ? 1 : 0, r(f.pose.x), r(f.pose.y), round_angle(f.pose.theta), f.action});
}

json feet_json(const std::vector<ReplayFoot>& feet, const Rounder& r) {
  json out = json::array();
  for (const auto& f : feet) out.push_back(foot_json(f, r));
  return out;
}

bool same_feet(const std::vector<ReplayFoot>& a, const std::vector<ReplayFoot>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].left != b[i].left || a[i].pose.x != b[i].pose.x || a[i].pose.y != b[i].pose.y ||
        a[i].pose.theta != b[i].pose.theta || a[i].action != b[i].action)
      return false;
  return true;
}

json footsteps_json(const ReplayFootsteps& f, const Rounder& r) {
  json taken = json::array();
  for (const auto& foot : f.taken) {
    json j = foot_json(foot, r);
    j.insert(j.begin(), std::round(foot.t_s * 1000.0) / 1000.0);
    taken.push_back(std::move(j));
  }
  return {{"foot", json::array({f.foot_length_m, f.foot_width_m})},
          {"taken", std::move(taken)},
          {"height_lo", f.height_lo_m},
          {"height_hi", f.height_hi_m}};
}

bool same_path(const Path& a, const Path& b) {
  if (a.poses.size() != b.poses.size()) return false;
  for (std::size_t i = 0; i < a.poses.size(); ++i)
    if (a.poses[i].x != b.poses[i].x || a.poses[i].y != b.poses[i].y) return false;
  return true;
}

// Frames carry paths and points only when they differ from the previous frame's (the page
// fills forward).
json frames_json(const ReplayData& data, const Rounder& r) {
  json out = json::array();
  const ReplayFrame* last = nullptr;
  std::string last_lidar, last_depth;
  for (const auto& f : data.frames) {
    require(f.actors.size() == data.actors.size(), "ReplayFrame.actors", "one pose per ReplayData actor");
    json j = {{"t", std::round(f.t_s * 1000.0) / 1000.0},
              {"true", pose_json(f.true_pose, r)},
              {"est", pose_json(f.estimated_pose, r)},
              {"cmd", json::array({r(f.cmd.linear_x), round_angle(f.cmd.angular_z)})},
              {"goal", f.goal ? pose_json(*f.goal, r) : json(nullptr)},
              {"node", f.active_node},
              {"state", f.state},
              {"outcome", f.outcome}};
    json actors = json::array();
    for (const auto& a : f.actors) actors.push_back(pose_json(a, r));
    j["actors"] = std::move(actors);
    if (!last || !same_path(last->global_path, f.global_path)) j["gp"] = path_json(f.global_path, r);
    if (!last || !same_path(last->local_trajectory, f.local_trajectory)) j["lt"] = path_json(f.local_trajectory, r);
    if (data.footsteps) {
      if (!last || !same_feet(last->plan, f.plan)) j["plan"] = feet_json(f.plan, r);
      if (f.replanned) j["replan"] = true;
    }
    for (auto [key, points, previous] :
         {std::tuple{"lidar", &f.lidar, &last_lidar}, {"depth", &f.depth, &last_depth}}) {
      std::string packed = points_packed(*points, r);
      if (last && packed == *previous) continue;
      j[key] = packed;
      *previous = std::move(packed);
    }
    last = &f;
    out.push_back(std::move(j));
  }
  return out;
}

}  // namespace

void ReplayHtmlParams::validate() const {
  require(std::isfinite(position_resolution_m) && position_resolution_m >= 1e-4 && position_resolution_m <= 0.1,
          "position_resolution_m", "in [0.0001, 0.1] m");
}

std::string replay_json(const ReplayData& data, const ReplayHtmlParams& params) {
  params.validate();
  const Rounder r(params.position_resolution_m);
  json j = {{"format", "bipednav-replay"},
            {"version", 1},
            {"title", data.title},
            {"summary", summary_json(data.summary, r)},
            {"robot_radius_m", data.robot_radius_m},
            {"point_step_m", 1.0 / r.scale()}};
  json statics = json::array();
  for (const auto& o : data.statics) statics.push_back(outline_json(o, r));
  j["statics"] = std::move(statics);
  json actors = json::array();
  for (const auto& a : data.actors) {
    json outlines = json::array();
    for (const auto& o : a.outlines) outlines.push_back(outline_json(o, r));
    actors.push_back({{"name", a.name}, {"outlines", std::move(outlines)}});
  }
  j["actors"] = std::move(actors);
  json goals = json::array();
  for (const auto& g : data.goals) goals.push_back({{"t", g.t_s}, {"pose", pose_json(g.pose, r)}});
  j["goals"] = std::move(goals);
  j["frames"] = frames_json(data, r);
  j["global_maps"] = grids_json(data.global_maps);
  j["local_maps"] = grids_json(data.local_maps);
  if (!data.local_planner.empty()) j["local_planner"] = data.local_planner;
  if (data.footsteps) {
    j["footsteps"] = footsteps_json(*data.footsteps, r);
    j["height_maps"] = grids_json(data.footsteps->height_maps);
  }
  return j.dump();
}

std::string replay_html(const ReplayData& data, const ReplayHtmlParams& params) {
  // '<' only occurs inside JSON strings, where \u003c is equivalent and cannot end the <script>.
  std::string payload;
  for (const char c : replay_json(data, params)) {
    if (c == '<')
      payload += "\\u003c";
    else
      payload += c;
  }
  std::string html(kReplayTemplate);
  const auto at = html.find(kPlaceholder);
  if (at == std::string::npos) throw Error("replay_html: the page template has no data placeholder");
  html.replace(at, kPlaceholder.size(), payload);
  return html;
}

void write_replay_html(const std::filesystem::path& file, const ReplayData& data, const ReplayHtmlParams& params) {
  const std::string html = replay_html(data, params);
  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  if (ec) throw FileError(file.parent_path().string(), "", "cannot create the directory: " + ec.message());
  std::ofstream out(file, std::ios::binary);
  if (!out) throw FileError(file.string(), "", "cannot open for writing");
  out << html;
  if (!out) throw FileError(file.string(), "", "write failed");
}

}  // namespace bipednav::viz
