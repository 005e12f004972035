// libFuzzer target: heightmap images (YAML + PNG). The input is the YAML, optionally followed by
// "\n%%IMAGE%%\n" and the PNG bytes, written as hm.png next to it.
#include "bipednav/mapping/map_io.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  const auto parts = fuzz::split(fuzz::as_text(data, size), "\n%%IMAGE%%\n", 2);
  const auto dir = fuzz::scratch_dir("heightmap_image");
  const auto yaml = fuzz::write_file(dir, "hm.yaml", parts[0]);
  fuzz::write_file(dir, "hm.png", parts.size() > 1 ? parts[1] : std::string_view{});
  fuzz::run_loader([&] { (void)mapping::read_heightmap_image(yaml); }, {dir.string()});
  return 0;
}
