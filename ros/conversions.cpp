#include "ros/conversions.hpp"

#include <sensor_msgs/point_field_conversion.h>

#include <cmath>
#include <cstring>

#include "bipednav/common/error.hpp"

namespace bipednav::ros1 {

ros::Time to_time(double stamp_s) {
  if (!std::isfinite(stamp_s) || stamp_s < 0.0) return ros::Time(0);
  return ros::Time(stamp_s);
}

namespace {

sensor_msgs::PointField field(const std::string& name, std::uint32_t offset, std::uint8_t type) {
  sensor_msgs::PointField f;
  f.name = name;
  f.offset = offset;
  f.datatype = type;
  f.count = 1;
  return f;
}

template <typename T>
void put(std::uint8_t* dst, T v) {
  std::memcpy(dst, &v, sizeof(T));
}

template <typename T>
T get(const std::uint8_t* src) {
  T v;
  std::memcpy(&v, src, sizeof(T));
  return v;
}

const sensor_msgs::PointField* find_field(const sensor_msgs::PointCloud2& msg, const std::string& name) {
  for (const auto& f : msg.fields)
    if (f.name == name) return &f;
  return nullptr;
}

// Reads a numeric field as double, whatever its declared datatype.
double read_number(const std::uint8_t* p, std::uint8_t type) {
  switch (type) {
    case sensor_msgs::PointField::INT8:
      return get<std::int8_t>(p);
    case sensor_msgs::PointField::UINT8:
      return get<std::uint8_t>(p);
    case sensor_msgs::PointField::INT16:
      return get<std::int16_t>(p);
    case sensor_msgs::PointField::UINT16:
      return get<std::uint16_t>(p);
    case sensor_msgs::PointField::INT32:
      return get<std::int32_t>(p);
    case sensor_msgs::PointField::UINT32:
      return get<std::uint32_t>(p);
    case sensor_msgs::PointField::FLOAT32:
      return get<float>(p);
    case sensor_msgs::PointField::FLOAT64:
      return get<double>(p);
    default:
      throw Error("PointCloud2: unsupported field datatype " + std::to_string(type));
  }
}

std::uint32_t datatype_size(std::uint8_t type) {
  switch (type) {
    case sensor_msgs::PointField::INT8:
    case sensor_msgs::PointField::UINT8:
      return 1;
    case sensor_msgs::PointField::INT16:
    case sensor_msgs::PointField::UINT16:
      return 2;
    case sensor_msgs::PointField::INT32:
    case sensor_msgs::PointField::UINT32:
    case sensor_msgs::PointField::FLOAT32:
      return 4;
    case sensor_msgs::PointField::FLOAT64:
      return 8;
    default:
      throw Error("PointCloud2: unsupported field datatype " + std::to_string(type));
  }
}

void check_layout(const sensor_msgs::PointCloud2& msg) {
  const std::size_t n = static_cast<std::size_t>(msg.width) * msg.height;
  if (msg.is_bigendian) throw Error("PointCloud2 '" + msg.header.frame_id + "': big-endian data is not supported");
  if (msg.row_step < msg.width * msg.point_step)
    throw Error("PointCloud2 '" + msg.header.frame_id + "': row_step smaller than width * point_step");
  if (msg.data.size() < static_cast<std::size_t>(msg.row_step) * msg.height || (n > 0 && msg.point_step == 0))
    throw Error("PointCloud2 '" + msg.header.frame_id + "': data shorter than height * row_step");
  for (const auto& f : msg.fields)
    if (f.offset + datatype_size(f.datatype) > msg.point_step)
      throw Error("PointCloud2 '" + msg.header.frame_id + "': field '" + f.name + "' outside point_step");
}

}  // namespace

sensor_msgs::PointCloud2 to_msg(const PointCloud& cloud) {
  require(cloud.is_consistent(), "PointCloud", "optional fields empty or one per point");
  sensor_msgs::PointCloud2 msg;
  msg.header.frame_id = cloud.frame_id;
  msg.header.stamp = to_time(cloud.stamp_s);
  std::uint32_t off = 0;
  for (const char* axis : {"x", "y", "z"}) {
    msg.fields.push_back(field(axis, off, sensor_msgs::PointField::FLOAT32));
    off += 4;
  }
  const std::uint32_t off_i = off, off_t = off + (cloud.has_intensity() ? 4 : 0);
  if (cloud.has_intensity()) msg.fields.push_back(field("intensity", off_i, sensor_msgs::PointField::FLOAT32));
  if (cloud.has_time()) msg.fields.push_back(field("time", off_t, sensor_msgs::PointField::FLOAT32));
  const std::uint32_t off_r = off_t + (cloud.has_time() ? 4 : 0);
  if (cloud.has_ring()) msg.fields.push_back(field("ring", off_r, sensor_msgs::PointField::UINT16));
  msg.point_step = off_r + (cloud.has_ring() ? 2 : 0);
  msg.height = 1;
  msg.width = static_cast<std::uint32_t>(cloud.size());
  msg.row_step = msg.point_step * msg.width;
  msg.is_bigendian = false;
  msg.is_dense = true;
  msg.data.resize(msg.row_step);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    std::uint8_t* p = msg.data.data() + i * msg.point_step;
    for (int k = 0; k < 3; ++k) put<float>(p + 4 * k, cloud.points[i][k]);
    if (cloud.has_intensity()) put<float>(p + off_i, cloud.intensities[i]);
    if (cloud.has_time()) put<float>(p + off_t, cloud.time_offsets_s[i]);
    if (cloud.has_ring()) put<std::uint16_t>(p + off_r, cloud.rings[i]);
  }
  return msg;
}

PointCloud from_msg(const sensor_msgs::PointCloud2& msg) {
  check_layout(msg);
  const auto *fx = find_field(msg, "x"), *fy = find_field(msg, "y"), *fz = find_field(msg, "z");
  if (!fx || !fy || !fz) throw Error("PointCloud2 '" + msg.header.frame_id + "': needs x, y and z fields");
  const auto* fi = find_field(msg, "intensity");
  const auto* ft = find_field(msg, "time");
  const auto* fr = find_field(msg, "ring");
  PointCloud cloud;
  cloud.frame_id = msg.header.frame_id;
  cloud.stamp_s = msg.header.stamp.toSec();
  const std::size_t n = static_cast<std::size_t>(msg.width) * msg.height;
  cloud.reserve(n);
  for (std::size_t r = 0; r < msg.height; ++r) {
    for (std::size_t c = 0; c < msg.width; ++c) {
      const std::uint8_t* p = msg.data.data() + r * msg.row_step + c * msg.point_step;
      const Eigen::Vector3f xyz(static_cast<float>(read_number(p + fx->offset, fx->datatype)),
                                static_cast<float>(read_number(p + fy->offset, fy->datatype)),
                                static_cast<float>(read_number(p + fz->offset, fz->datatype)));
      if (!xyz.allFinite()) continue;
      cloud.points.push_back(xyz);
      if (fi) cloud.intensities.push_back(static_cast<float>(read_number(p + fi->offset, fi->datatype)));
      if (ft) cloud.time_offsets_s.push_back(static_cast<float>(read_number(p + ft->offset, ft->datatype)));
      if (fr) cloud.rings.push_back(static_cast<std::uint16_t>(read_number(p + fr->offset, fr->datatype)));
    }
  }
  return cloud;
}

std::int8_t occupancy_of(std::uint8_t cost) {
  if (cost == mapping::kUnknown) return -1;
  if (cost == mapping::kLethal) return 100;
  if (cost == 0) return 0;
  return static_cast<std::int8_t>(1 + (98 * (cost - 1)) / 252);  // 1..99 for 1..253
}

nav_msgs::OccupancyGrid to_msg(const mapping::Costmap2D& map, const std::string& frame_id, double stamp_s) {
  nav_msgs::OccupancyGrid msg;
  msg.header.frame_id = frame_id;
  msg.header.stamp = to_time(stamp_s);
  msg.info.map_load_time = msg.header.stamp;
  msg.info.resolution = static_cast<float>(map.resolution_m());
  msg.info.width = static_cast<std::uint32_t>(map.width());
  msg.info.height = static_cast<std::uint32_t>(map.height());
  msg.info.origin = to_pose_msg(Pose2{map.geometry().origin_x_m, map.geometry().origin_y_m, 0.0});
  msg.data.resize(map.data().size());
  // Both use row-major storage with row 0 at the origin's y.
  for (std::size_t i = 0; i < map.data().size(); ++i) msg.data[i] = occupancy_of(map.data()[i]);
  return msg;
}

mapping::Costmap2D from_msg(const nav_msgs::OccupancyGrid& msg) {
  mapping::GridGeometry g;
  g.width = static_cast<int>(msg.info.width);
  g.height = static_cast<int>(msg.info.height);
  g.resolution_m = msg.info.resolution;
  g.origin_x_m = msg.info.origin.position.x;
  g.origin_y_m = msg.info.origin.position.y;
  if (msg.data.size() != g.size()) throw Error("OccupancyGrid: data size differs from width * height");
  if (!(g.resolution_m > 0.0)) throw Error("OccupancyGrid: resolution must be > 0");
  mapping::Costmap2D map(g);
  for (std::size_t i = 0; i < msg.data.size(); ++i) {
    const int v = msg.data[i];
    map.data()[i] = v < 0      ? mapping::kUnknown
                    : v >= 100 ? mapping::kLethal
                    : v == 0   ? 0
                               : static_cast<std::uint8_t>(1 + ((v - 1) * 252) / 98);
  }
  return map;
}

nav_msgs::Path to_msg(const Path& path, double stamp_s) {
  nav_msgs::Path msg;
  msg.header.frame_id = path.frame_id;
  msg.header.stamp = to_time(stamp_s);
  msg.poses.reserve(path.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    const double t = path.times_s.size() == path.size() ? stamp_s + path.times_s[i] : stamp_s;
    msg.poses.push_back(to_pose_stamped(path.poses[i], path.frame_id, t));
  }
  return msg;
}

Path from_msg(const nav_msgs::Path& msg) {
  Path path;
  path.frame_id = msg.header.frame_id;
  const double t0 = msg.header.stamp.toSec();
  bool timed = false;
  for (const auto& p : msg.poses) {
    path.poses.push_back(from_msg(p.pose));
    path.times_s.push_back(p.header.stamp.toSec() - t0);
    timed = timed || path.times_s.back() != 0.0;
  }
  if (!timed) path.times_s.clear();
  return path;
}

geometry_msgs::Twist to_msg(const Twist& t) {
  geometry_msgs::Twist msg;
  msg.linear.x = t.linear_x;
  msg.linear.y = t.linear_y;
  msg.angular.z = t.angular_z;
  return msg;
}

Twist from_msg(const geometry_msgs::Twist& msg) { return Twist{msg.linear.x, msg.linear.y, msg.angular.z}; }

geometry_msgs::Pose to_pose_msg(const Pose2& p) {
  geometry_msgs::Pose msg;
  msg.position.x = p.x;
  msg.position.y = p.y;
  msg.orientation.z = std::sin(p.theta / 2.0);
  msg.orientation.w = std::cos(p.theta / 2.0);
  return msg;
}

Pose2 from_msg(const geometry_msgs::Pose& msg) {
  const auto& q = msg.orientation;
  const double yaw = std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
  Pose2 p{msg.position.x, msg.position.y, yaw};
  if (!p.is_finite() || !std::isfinite(q.w)) throw Error("geometry_msgs/Pose: non-finite position or orientation");
  return p;
}

geometry_msgs::PoseStamped to_pose_stamped(const Pose2& p, const std::string& frame_id, double stamp_s) {
  geometry_msgs::PoseStamped msg;
  msg.header.frame_id = frame_id;
  msg.header.stamp = to_time(stamp_s);
  msg.pose = to_pose_msg(p);
  return msg;
}

geometry_msgs::TransformStamped to_transform(const SE3& T, const std::string& parent, const std::string& child,
                                             double stamp_s) {
  geometry_msgs::TransformStamped msg;
  msg.header.frame_id = parent;
  msg.header.stamp = to_time(stamp_s);
  msg.child_frame_id = child;
  msg.transform.translation.x = T.translation().x();
  msg.transform.translation.y = T.translation().y();
  msg.transform.translation.z = T.translation().z();
  const Eigen::Quaterniond q(T.linear());
  msg.transform.rotation.x = q.x();
  msg.transform.rotation.y = q.y();
  msg.transform.rotation.z = q.z();
  msg.transform.rotation.w = q.w();
  return msg;
}

geometry_msgs::TransformStamped to_transform(const Pose2& T, const std::string& parent, const std::string& child,
                                             double stamp_s) {
  return to_transform(se3_from_pose2(T), parent, child, stamp_s);
}

nav_msgs::Odometry to_msg(const Odometry& odom, const std::string& odom_frame, const std::string& base_frame) {
  nav_msgs::Odometry msg;
  msg.header.frame_id = odom_frame;
  msg.header.stamp = to_time(odom.stamp_s);
  msg.child_frame_id = base_frame;
  const Eigen::Quaterniond q(rpy_to_matrix(odom.roll_rad, odom.pitch_rad, odom.T_odom_base.theta));
  msg.pose.pose.position.x = odom.T_odom_base.x;
  msg.pose.pose.position.y = odom.T_odom_base.y;
  msg.pose.pose.orientation.x = q.x();
  msg.pose.pose.orientation.y = q.y();
  msg.pose.pose.orientation.z = q.z();
  msg.pose.pose.orientation.w = q.w();
  msg.twist.twist = to_msg(odom.velocity);
  return msg;
}

Odometry from_msg(const nav_msgs::Odometry& msg) {
  Odometry o;
  o.stamp_s = msg.header.stamp.toSec();
  o.T_odom_base = from_msg(msg.pose.pose);
  const auto& q = msg.pose.pose.orientation;
  const Eigen::Vector3d rpy = matrix_to_rpy(Eigen::Quaterniond(q.w, q.x, q.y, q.z).normalized().toRotationMatrix());
  o.roll_rad = rpy.x();
  o.pitch_rad = rpy.y();
  o.velocity = from_msg(msg.twist.twist);
  return o;
}

}  // namespace bipednav::ros1
