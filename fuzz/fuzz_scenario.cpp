// libFuzzer target: scenario files (sim/scenario load_scenario). The input is the scenario YAML,
// optionally followed by "\n%%WORLD%%\n" and an SDF world written as world.sdf next to it (for
// `world_file: world.sdf`).
#include "bipednav/sim/scenario.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  const auto parts = fuzz::split(fuzz::as_text(data, size), "\n%%WORLD%%\n", 2);
  const auto dir = fuzz::scratch_dir("scenario");
  const auto file = fuzz::write_file(dir, "scenario.yaml", parts[0]);
  fuzz::write_file(dir, "world.sdf", parts.size() > 1 ? parts[1] : std::string_view{});
  fuzz::run_loader(
      [&] {
        const sim::Scenario s = sim::load_scenario(file);
        (void)s.goal_at(1.0);
        (void)s.command_at(1.0);
      },
      {dir.string()});
  return 0;
}
