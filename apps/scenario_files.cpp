#include "apps/scenario_files.hpp"

#include "bipednav/common/error.hpp"

#ifndef BIPEDNAV_SOURCE_DIR
#define BIPEDNAV_SOURCE_DIR "."
#endif

namespace bipednav::app {

std::filesystem::path scenario_dir() { return std::filesystem::path(BIPEDNAV_SOURCE_DIR) / "scenarios"; }

std::filesystem::path resolve_scenario(const std::string& name) {
  if (std::filesystem::exists(name)) return name;
  const auto p = scenario_dir() / (name + ".yaml");
  if (std::filesystem::exists(p)) return p;
  throw Error("no scenario '" + name + "' (neither a file nor scenarios/" + name + ".yaml)");
}

}  // namespace bipednav::app
