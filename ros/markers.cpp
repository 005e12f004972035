#include <cmath>

#include "ros/conversions.hpp"

namespace bipednav::ros1 {

namespace {

visualization_msgs::Marker marker(const MarkerInput& in, const std::string& ns, int type) {
  visualization_msgs::Marker m;
  m.header.frame_id = in.frame_id;
  m.header.stamp = to_time(in.stamp_s);
  m.ns = ns;
  m.id = 0;
  m.type = type;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.color.a = 1.0;
  return m;
}

void color(visualization_msgs::Marker& m, float r, float g, float b, float a = 1.0f) {
  m.color.r = r;
  m.color.g = g;
  m.color.b = b;
  m.color.a = a;
}

// Lethal cells of the local costmap as one cube list.
visualization_msgs::Marker obstacle_marker(const MarkerInput& in) {
  auto m = marker(in, "obstacles", visualization_msgs::Marker::CUBE_LIST);
  color(m, 0.9f, 0.1f, 0.1f, 0.8f);
  const auto& map = *in.local_costmap;
  m.scale.x = m.scale.y = map.resolution_m();
  m.scale.z = 0.05;
  for (int y = 0; y < map.height(); ++y)
    for (int x = 0; x < map.width(); ++x)
      if (map.cost(x, y) == mapping::kLethal) {
        const Eigen::Vector2d c = map.geometry().cell_center(x, y);
        geometry_msgs::Point p;
        p.x = c.x();
        p.y = c.y();
        p.z = 0.025;
        m.points.push_back(p);
      }
  return m;
}

// Alternating left/right feet every step_length_m along the local trajectory.
visualization_msgs::Marker footstep_marker(const MarkerInput& in) {
  auto m = marker(in, "footsteps", visualization_msgs::Marker::CUBE_LIST);
  color(m, 0.1f, 0.4f, 0.9f, 0.9f);
  m.scale.x = 0.2;
  m.scale.y = 0.1;
  m.scale.z = 0.02;
  const auto& poses = in.local_trajectory->poses;
  double since = in.step_length_m;
  bool left = true;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (i > 0) since += distance(poses[i - 1], poses[i]);
    if (since < in.step_length_m) continue;
    since = 0.0;
    const double side = (left ? 0.5 : -0.5) * in.step_width_m;
    const Pose2 foot = poses[i] * Pose2{0.0, side, 0.0};
    geometry_msgs::Point p;
    p.x = foot.x;
    p.y = foot.y;
    p.z = 0.01;
    m.points.push_back(p);
    left = !left;
  }
  return m;
}

}  // namespace

visualization_msgs::MarkerArray to_markers(const MarkerInput& in) {
  visualization_msgs::MarkerArray out;
  auto fp = marker(in, "footprint", visualization_msgs::Marker::CYLINDER);
  fp.pose = to_pose_msg(in.robot);
  fp.scale.x = fp.scale.y = 2.0 * in.footprint_radius_m;
  fp.scale.z = 0.02;
  color(fp, 0.2f, 0.8f, 0.2f, 0.5f);
  out.markers.push_back(fp);
  auto goal = marker(in, "goal", visualization_msgs::Marker::ARROW);
  if (in.goal) {
    goal.pose = to_pose_msg(*in.goal);
    goal.scale.x = 0.4;
    goal.scale.y = goal.scale.z = 0.06;
    color(goal, 1.0f, 0.6f, 0.0f);
  } else {
    goal.action = visualization_msgs::Marker::DELETE;
  }
  out.markers.push_back(goal);
  if (in.local_costmap) out.markers.push_back(obstacle_marker(in));
  if (in.local_trajectory && in.step_length_m > 0.0) out.markers.push_back(footstep_marker(in));
  return out;
}

}  // namespace bipednav::ros1
