#include "bipednav/sim/sdf_writer.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <variant>

#include "bipednav/common/error.hpp"

namespace bipednav::sim {
namespace {

// The shortest text that reads back to the same double.
std::string number(double v) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, v).ptr;
  return std::string(text, end);
}

// "x y z roll pitch yaw" with R = Rz(yaw) Ry(pitch) Rx(roll), as SDF reads it.
std::string pose_text(const SE3& T) {
  const Eigen::Vector3d ypr = T.linear().eulerAngles(2, 1, 0);
  const Eigen::Vector3d& p = T.translation();
  return number(p.x()) + " " + number(p.y()) + " " + number(p.z()) + " " + number(ypr[2]) + " " + number(ypr[1]) + " " +
         number(ypr[0]);
}

std::string shape_xml(const Shape& shape, const std::string& name) {
  if (const auto* b = std::get_if<Box>(&shape))
    return "<box><size>" + number(b->size_m.x()) + " " + number(b->size_m.y()) + " " + number(b->size_m.z()) +
           "</size></box>";
  if (const auto* c = std::get_if<Cylinder>(&shape))
    return "<cylinder><radius>" + number(c->radius_m) + "</radius><length>" + number(c->length_m) +
           "</length></cylinder>";
  if (const auto* s = std::get_if<Sphere>(&shape))
    return "<sphere><radius>" + number(s->radius_m) + "</radius></sphere>";
  if (const auto* p = std::get_if<Plane>(&shape))
    return "<plane><normal>" + number(p->normal.x()) + " " + number(p->normal.y()) + " " + number(p->normal.z()) +
           "</normal><size>" + number(p->size_m.x()) + " " + number(p->size_m.y()) + "</size></plane>";
  throw Error("write_sdf_world: '" + name + "' is a mesh; only boxes, cylinders, spheres and planes can be written");
}

// A collision and a visual of the same geometry, posed in their link.
std::string body_xml(const std::string& name, const SE3& T_link_shape, const Shape& shape) {
  const std::string inner =
      "<pose>" + pose_text(T_link_shape) + "</pose><geometry>" + shape_xml(shape, name) + "</geometry>";
  return "      <collision name=\"" + name + "\">" + inner + "</collision>\n      <visual name=\"" + name + "\">" +
         inner + "</visual>\n";
}

bool has_ground(const World& world) {
  for (const Geometry& g : world.statics)
    if (const auto* p = std::get_if<Plane>(&g.shape); p && std::abs((g.T_parent_shape.linear() * p->normal).z()) > 0.99)
      return true;
  return false;
}

void append_statics(const World& world, std::ostringstream& out) {
  std::size_t i = 0;
  while (i < world.statics.size()) {
    const std::string& first = world.statics[i].name;
    const std::string model = first.substr(0, first.find("::"));
    out << "  <model name=\"" << model << "\">\n    <static>true</static>\n    <link name=\"link\">\n";
    for (; i < world.statics.size(); ++i) {
      const Geometry& g = world.statics[i];
      const auto sep = g.name.find("::");
      if (g.name.substr(0, sep) != model) break;
      out << body_xml(sep == std::string::npos ? g.name : g.name.substr(sep + 2), g.T_parent_shape, g.shape);
    }
    out << "    </link>\n  </model>\n";
  }
}

void append_actor(const Actor& a, std::ostringstream& out) {
  out << "  <actor name=\"" << a.name << "\">\n    <link name=\"body\">\n";
  for (const Geometry& g : a.parts) out << body_xml(g.name, g.T_parent_shape, g.shape);
  out << "    </link>\n    <script>\n      <loop>" << (a.loop ? "true" : "false") << "</loop>\n      <delay_start>"
      << number(a.delay_s) << "</delay_start>\n      <auto_start>true</auto_start>\n"
      << "      <trajectory id=\"0\" type=\"walking\">\n";
  for (const Waypoint& w : a.trajectory)
    out << "        <waypoint><time>" << number(w.time_s) << "</time><pose>" << pose_text(w.pose)
        << "</pose></waypoint>\n";
  out << "      </trajectory>\n    </script>\n  </actor>\n";
}

}  // namespace

std::string sdf_world_xml(const World& world) {
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n<sdf version=\"1.7\">\n<world name=\"" << (world.name.empty() ? "world" : world.name)
      << "\">\n";
  if (!has_ground(world))
    out << "  <model name=\"ground_plane\">\n    <static>true</static>\n    <link name=\"link\">\n"
        << body_xml("ground", SE3::Identity(), Plane{}) << "    </link>\n  </model>\n";
  append_statics(world, out);
  for (const Actor& a : world.actors) append_actor(a, out);
  out << "</world>\n</sdf>\n";
  return out.str();
}

void write_sdf_world(const World& world, const std::filesystem::path& file) {
  const std::string xml = sdf_world_xml(world);
  std::ofstream f(file);
  if (!f || !(f << xml) || !f.flush()) throw FileError(file.string(), "", "cannot write the world file");
}

}  // namespace bipednav::sim
