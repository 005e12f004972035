// libFuzzer target: PLY reader (ascii and binary_little_endian).
#include "bipednav/io/ply.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  fuzz::run_loader([&] { (void)io::parse_ply(fuzz::as_text(data, size), "fuzz.ply"); }, {"fuzz.ply"});
  return 0;
}
