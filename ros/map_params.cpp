#include "ros/map_params.hpp"

#include "bipednav/common/error.hpp"

namespace bipednav::ros1 {

std::map<std::string, double> to_param(MapParams p) {
  std::map<std::string, double> values;
  p.fields([&](const char* name, double& v) { values[name] = v; });
  return values;
}

void apply_param(const std::map<std::string, double>& values, const std::string& param_name, MapParams& p) {
  std::map<std::string, double*> field;
  std::string known;
  p.fields([&](const char* name, double& v) {
    field[name] = &v;
    known += (known.empty() ? "" : ", ") + std::string(name);
  });
  for (const auto& entry : values)
    if (!field.count(entry.first))
      throw Error("parameter " + param_name + ": unknown key '" + entry.first + "' (expected " + known + ")");
  for (const auto& [key, value] : values) *field[key] = value;
}

}  // namespace bipednav::ros1
