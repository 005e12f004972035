#include "bipednav/navigation/robot_loading.hpp"

#include <algorithm>
#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/io/robot_profile_yaml.hpp"
#include "bipednav/navigation/navigator_params_yaml.hpp"

namespace bipednav::navigation {

RobotProfile load_robot(const std::string& name_or_file, const std::filesystem::path& config_dir) {
  namespace fs = std::filesystem;
  const fs::path given(name_or_file);
  const std::string ext = given.extension().string();
  if (ext == ".yaml" || ext == ".yml" || name_or_file.find('/') != std::string::npos) {
    if (!fs::is_regular_file(given)) throw Error("robot profile file " + name_or_file + " not found");
    return io::load_robot_profile(given);
  }
  const fs::path dir = config_dir.empty() ? fs::path(navigation::config_dir()) : config_dir;
  const fs::path file = dir / (name_or_file + ".yaml");
  if (name_or_file.empty() || !fs::exists(file)) {
    std::vector<std::string> known;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().extension() == ".yaml") known.push_back(e.path().stem().string());
    std::sort(known.begin(), known.end());
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    throw Error(
        "unknown robot '" + name_or_file + "': no profile " + file.string() +
        (list.empty() ? "" : " (profiles in " + dir.string() + ": " + list + "; or give a profile file FILE.yaml)"));
  }
  return io::load_robot_profile(file);
}

NavigatorParams navigator_params_for(const RobotProfile& robot, const std::filesystem::path& params_file) {
  NavigatorParams p = NavigatorParams::for_robot(robot);
  if (!params_file.empty()) apply_navigator_params_file(params_file, p);
  return p;
}

}  // namespace bipednav::navigation
