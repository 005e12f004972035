#include "bipednav/io/robot_profile_yaml.hpp"

namespace bipednav::io {
namespace {

SensorMount read_mount(ParamReader& r) {
  SensorMount m;
  r.require("name", m.name);
  r.require("type", m.type);
  r.get("x_m", m.x_m);
  r.get("y_m", m.y_m);
  r.get("z_m", m.z_m);
  r.get("roll_rad", m.roll_rad);
  r.get("pitch_rad", m.pitch_rad);
  r.get("yaw_rad", m.yaw_rad);
  r.finish();
  return m;
}

}  // namespace

RobotProfile read_robot_profile(ParamReader& r) {
  RobotProfile p;
  r.get("name", p.name);
  r.get("kind", p.kind);
  r.get("footprint_radius_m", p.footprint_radius_m);
  r.get("height_m", p.height_m);
  auto get = [&r](const char* key, double& value) { r.get(key, value); };
  p.limits.visit_fields(get);  // flat: the limits' keys sit at the top level
  r.get("tracking_time_constant_s", p.tracking_time_constant_s);
  r.get("sway_amplitude_m", p.sway_amplitude_m);
  r.get("step_frequency_hz", p.step_frequency_hz);
  r.get("can_rotate_in_place", p.can_rotate_in_place);
  for (ParamReader& s : r.children("sensors")) p.sensors.push_back(read_mount(s));
  r.finish();
  try {
    p.validate();
  } catch (const ParamError& e) {
    throw FileError(r.file(), "", e.what());
  }
  return p;
}

RobotProfile load_robot_profile(const std::filesystem::path& file) {
  ParamReader r = ParamReader::from_file(file);
  return read_robot_profile(r);
}

RobotProfile parse_robot_profile(const std::string& yaml, const std::string& name) {
  ParamReader r = ParamReader::from_string(yaml, name);
  return read_robot_profile(r);
}

}  // namespace bipednav::io
