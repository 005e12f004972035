// libFuzzer target: Moving AI .scen reader.
#include "bipednav/io/movingai.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  const std::string text(fuzz::as_text(data, size));
  fuzz::run_loader([&] { (void)io::parse_movingai_scen(text, "fuzz.scen"); }, {"fuzz.scen"});
  return 0;
}
