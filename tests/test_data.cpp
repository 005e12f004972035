#include "test_data.hpp"

namespace bipednav::test {

std::filesystem::path data_file(const std::string& rel) {
  for (const std::filesystem::path root : {BIPEDNAV_TEST_DATA_DIR, BIPEDNAV_SHARED_DATA_DIR}) {
    const auto p = root / rel;
    if (std::filesystem::exists(p)) return p;
  }
  return {};
}

std::string missing_data(const std::string& rel) {
  return "SKIPPED: data file '" + rel + "' is neither in tests/data nor in ../shared/data";
}

std::filesystem::path source_dir() { return BIPEDNAV_SOURCE_DIR; }

}  // namespace bipednav::test
