#pragma once

// Shared helpers of the libFuzzer targets: a per-process scratch directory for loaders that take
// a path, splitting one input into several files, and the acceptance rule for rejected input.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "bipednav/common/error.hpp"

namespace bipednav::fuzz {

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// /tmp/bipednav-fuzz-<pid>/<target>: one per process, so parallel fuzzers (-jobs) do not collide.
inline std::filesystem::path scratch_dir(const std::string& target) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("bipednav-fuzz-" + std::to_string(::getpid())) / target;
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::filesystem::path write_file(const std::filesystem::path& dir, const std::string& name,
                                        std::string_view bytes) {
  const std::filesystem::path p = dir / name;
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return p;
}

// Splits `text` at each `separator` (a line of its own in the seeds, e.g. "\n%%FILE%%\n").
inline std::vector<std::string_view> split(std::string_view text, std::string_view separator, std::size_t max_parts) {
  std::vector<std::string_view> parts;
  while (parts.size() + 1 < max_parts) {
    const std::size_t at = text.find(separator);
    if (at == std::string_view::npos) break;
    parts.push_back(text.substr(0, at));
    text.remove_prefix(at + separator.size());
  }
  parts.push_back(text);
  return parts;
}

[[noreturn]] inline void reject_unclear(const std::string& why, const char* message) {
  std::fprintf(stderr, "bipednav-fuzz: %s: \"%s\"\n", why.c_str(), message);
  std::abort();
}

// Runs one load. Rejections must be a bipednav::Error; a FileError must name one of `names`
// (the file, or a file it refers to), a ParamError is accepted only where a parameter struct's
// validate() is the documented check (`allow_param_error`). Anything else escapes and libFuzzer
// reports it as a crash.
template <class Fn>
void run_loader(Fn&& fn, const std::vector<std::string>& names, bool allow_param_error = false) {
  try {
    fn();
  } catch (const ParamError& e) {
    if (!allow_param_error) reject_unclear("ParamError where a FileError naming the file was expected", e.what());
  } catch (const Error& e) {
    const std::string msg = e.what();
    if (dynamic_cast<const FileError*>(&e) == nullptr) reject_unclear("not a FileError", e.what());
    bool named = false;
    for (const std::string& n : names) named = named || msg.find(n) != std::string::npos;
    if (!named) reject_unclear("FileError does not name the file", e.what());
  }
}

}  // namespace bipednav::fuzz
