// libFuzzer target: map_server maps (YAML + PGM/PNG image). The input is the YAML, optionally
// followed by "\n%%IMAGE%%\n" and the image bytes, written as map.pgm and map.png next to it.
#include "bipednav/mapping/map_io.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  const auto parts = fuzz::split(fuzz::as_text(data, size), "\n%%IMAGE%%\n", 2);
  const auto dir = fuzz::scratch_dir("map_server");
  const auto yaml = fuzz::write_file(dir, "map.yaml", parts[0]);
  const std::string_view image = parts.size() > 1 ? parts[1] : std::string_view{};
  fuzz::write_file(dir, "map.pgm", image);
  fuzz::write_file(dir, "map.png", image);
  fuzz::run_loader([&] { (void)mapping::read_map_server(yaml); }, {dir.string()});
  return 0;
}
