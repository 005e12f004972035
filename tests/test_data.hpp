#pragma once

#include <filesystem>
#include <string>

namespace bipednav::test {

// Locates a data file: first the project's own copy under tests/data/<rel>, then
// ../shared/data/<rel>. Returns an empty path when neither exists; callers then
// GTEST_SKIP() with the message from missing_data().
std::filesystem::path data_file(const std::string& rel);
std::string missing_data(const std::string& rel);
std::filesystem::path source_dir();

}  // namespace bipednav::test

// Skips the current test (visibly) when a data file is absent.
#define BIPEDNAV_REQUIRE_DATA(var, rel)                               \
  const std::filesystem::path var = ::bipednav::test::data_file(rel); \
  if (var.empty()) GTEST_SKIP() << ::bipednav::test::missing_data(rel)
