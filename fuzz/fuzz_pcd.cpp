// libFuzzer target: PCD reader (ascii, binary, binary_compressed), plus a write/read round trip
// of every cloud it accepts.
#include "bipednav/io/pcd.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace bipednav;
  fuzz::run_loader(
      [&] {
        const PointCloud cloud = io::parse_pcd(fuzz::as_text(data, size), "fuzz.pcd");
        const PointCloud again = io::parse_pcd(io::pcd_bytes(cloud, io::PcdEncoding::binary_compressed), "again.pcd");
        if (again.size() != cloud.size()) std::abort();
      },
      {"fuzz.pcd"});
  return 0;
}
