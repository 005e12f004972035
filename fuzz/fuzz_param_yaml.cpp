// libFuzzer target: YAML parameters through io::ParamReader into a component parameter struct
// (io::HeightmapImageParams, validate()d) plus every reader operation: scalars of each type,
// lists, a nested mapping, a list of mappings, required keys and the unknown-key check; and the
// navigation parameters file (navigation::read_navigator_params) under the key `navigator`, and the
// footstep navigator's (FootstepNavigatorParams) under `footstep_navigator`.
#include <string>
#include <vector>

#include "bipednav/io/heightmap_image.hpp"
#include "bipednav/io/param_reader.hpp"
#include "bipednav/navigation/navigator_params_yaml.hpp"
#include "fuzz_common.hpp"

namespace {

void read_component(bipednav::io::ParamReader& r) {
  bipednav::io::HeightmapImageParams p;
  r.get("resolution_m", p.resolution_m);
  r.get("min_height_m", p.min_height_m);
  r.get("max_height_m", p.max_height_m);
  r.get("origin_x_m", p.origin_x_m);
  r.get("origin_y_m", p.origin_y_m);
  p.validate();
}

void read_all(bipednav::io::ParamReader& r) {
  std::string name;
  int count = 0;
  bool enabled = false;
  std::uint64_t seed = 0;
  std::vector<double> values;
  std::vector<std::string> names;
  r.get("name", name);
  r.get("count", count);
  r.get("enabled", enabled);
  r.get("seed", seed);
  r.get("values", values);
  r.get("names", names);
  if (r.has("required")) r.require("required", name);
  bipednav::io::ParamReader c = r.child("component");
  read_component(c);
  c.finish();
  for (bipednav::io::ParamReader& item : r.children("items")) {
    double x_m = 0.0;
    item.get("x_m", x_m);
    item.finish();
  }
  if (r.has("navigator")) {
    bipednav::io::ParamReader nav = r.child("navigator");
    bipednav::navigation::NavigatorParams p =
        bipednav::navigation::NavigatorParams::for_robot(bipednav::RobotProfile{});
    bipednav::navigation::read_navigator_params(nav, p);
    (void)bipednav::navigation::navigator_params_yaml(p);
  }
  if (r.has("footstep_navigator")) {
    bipednav::io::ParamReader nav = r.child("footstep_navigator");
    bipednav::navigation::FootstepNavigatorParams p;
    bipednav::navigation::read_navigator_params(nav, p);
    (void)bipednav::navigation::navigator_params_yaml(p);
  }
  r.finish();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  const std::string text(fuzz::as_text(data, size));
  fuzz::run_loader(
      [&] {
        io::ParamReader r = io::ParamReader::from_string(text, "fuzz.yaml");
        read_all(r);
      },
      {"fuzz.yaml"}, /*allow_param_error=*/true);
  return 0;
}
