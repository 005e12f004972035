#include "bipednav/navigation/robot_loading.hpp"

#include <algorithm>
#include <vector>

#include "bipednav/common/error.hpp"
#include "bipednav/io/robot_profile_yaml.hpp"
#include "bipednav/navigation/navigator_params_yaml.hpp"

namespace bipednav::navigation {

namespace {

constexpr const char* kParamsSuffix = ".params.yaml";

// A robot's navigation tuning (robot_params_file), not a profile.
bool is_params_file(const std::filesystem::path& file) { return file.filename().string().ends_with(kParamsSuffix); }

// The folder of the robot files: the given one, or config_dir() when none is given.
std::filesystem::path robot_dir(const std::filesystem::path& config_dir) {
  return config_dir.empty() ? std::filesystem::path(navigation::config_dir()) : config_dir;
}

template <class P>
P layered(P p, const RobotProfile& robot, const std::filesystem::path& params_file,
          const std::filesystem::path& config_dir) {
  if (const auto own = robot_params_file(robot, config_dir); !own.empty()) apply_navigator_params_file(own, p);
  if (!params_file.empty()) apply_navigator_params_file(params_file, p);
  return p;
}

}  // namespace

RobotProfile load_robot(const std::string& name_or_file, const std::filesystem::path& config_dir) {
  namespace fs = std::filesystem;
  const fs::path given(name_or_file);
  const std::string ext = given.extension().string();
  if (ext == ".yaml" || ext == ".yml" || name_or_file.find('/') != std::string::npos) {
    if (!fs::is_regular_file(given)) throw Error("robot profile file " + name_or_file + " not found");
    return io::load_robot_profile(given);
  }
  const fs::path dir = robot_dir(config_dir);
  const fs::path file = dir / (name_or_file + ".yaml");
  if (name_or_file.empty() || !fs::exists(file) || is_params_file(file)) {
    std::vector<std::string> known;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().extension() == ".yaml" && !is_params_file(e.path())) known.push_back(e.path().stem().string());
    std::sort(known.begin(), known.end());
    std::string list;
    for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
    throw Error(
        "unknown robot '" + name_or_file + "': no profile " + file.string() +
        (list.empty() ? "" : " (profiles in " + dir.string() + ": " + list + "; or give a profile file FILE.yaml)"));
  }
  return io::load_robot_profile(file);
}

std::filesystem::path robot_params_file(const RobotProfile& robot, const std::filesystem::path& config_dir) {
  const std::filesystem::path file = robot_dir(config_dir) / (robot.name + kParamsSuffix);
  return std::filesystem::is_regular_file(file) ? file : std::filesystem::path();
}

NavigatorParams navigator_params_for(const RobotProfile& robot, const std::filesystem::path& params_file,
                                     const std::filesystem::path& config_dir) {
  return layered(NavigatorParams::for_robot(robot), robot, params_file, config_dir);
}

FootstepNavigatorParams footstep_navigator_params_for(const RobotProfile& robot,
                                                      const std::filesystem::path& params_file,
                                                      const std::filesystem::path& config_dir) {
  return layered(FootstepNavigatorParams{}, robot, params_file, config_dir);
}

}  // namespace bipednav::navigation
