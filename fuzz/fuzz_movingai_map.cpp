// libFuzzer target: Moving AI .map reader.
#include "bipednav/io/movingai.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  const std::string text(fuzz::as_text(data, size));
  fuzz::run_loader(
      [&] {
        const io::MovingAiMap m = io::parse_movingai_map(text, "fuzz.map");
        int passable = 0;
        for (int y = 0; y < m.height; ++y)
          for (int x = 0; x < m.width; ++x) passable += m.passable(x, y) ? 1 : 0;
        (void)passable;
      },
      {"fuzz.map"});
  return 0;
}
