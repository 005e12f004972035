// libFuzzer target: SDF worlds through libsdformat into a World (sim/sdf_world).
#include "bipednav/sim/sdf_world.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  const auto dir = fuzz::scratch_dir("sdf_world");
  const auto world = fuzz::write_file(dir, "fuzz.world", fuzz::as_text(data, size));
  fuzz::run_loader([&] { (void)sim::load_sdf_world(world); }, {dir.string()});
  return 0;
}
