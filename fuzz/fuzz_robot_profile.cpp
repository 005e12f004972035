// libFuzzer target: robot profile YAML (config/*.yaml) into a validated RobotProfile.
#include "bipednav/io/robot_profile_yaml.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  const std::string text(fuzz::as_text(data, size));
  fuzz::run_loader([&] { (void)io::parse_robot_profile(text, "fuzz_robot.yaml"); }, {"fuzz_robot.yaml"});
  return 0;
}
