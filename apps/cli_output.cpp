#include "apps/cli_output.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

#include "bipednav/common/error.hpp"

namespace bipednav::app {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void cannot_write(const std::string& flag, const fs::path& what, const std::string& why) {
  throw Error(flag + " " + what.string() + ": " + why);
}

void create_dirs(const fs::path& dir, const std::string& flag) {
  if (dir.empty()) return;
  std::error_code ec;
  if (fs::is_directory(dir, ec)) return;
  if (fs::exists(dir, ec)) cannot_write(flag, dir, "exists and is not a directory");
  fs::create_directories(dir, ec);
  if (ec) cannot_write(flag, dir, "cannot create the directory (" + ec.message() + ")");
}

// Opens `file` for appending (creating it when absent) and reports why not.
std::string try_open(const fs::path& file) {
  errno = 0;
  std::ofstream probe(file, std::ios::app | std::ios::binary);
  if (probe) return {};
  return errno ? std::strerror(errno) : "cannot open it for writing";
}

}  // namespace

void prepare_output_dir(const fs::path& dir, const std::string& flag) {
  create_dirs(dir, flag);
  const fs::path probe = dir / (".bipednav-write-probe-" + std::to_string(::getpid()));
  const std::string why = try_open(probe);
  std::error_code ec;
  fs::remove(probe, ec);
  if (!why.empty()) cannot_write(flag, dir, "cannot write in the directory (" + why + ")");
}

void prepare_output_file(const fs::path& file, const std::string& flag) {
  if (file.empty()) throw Error(flag + ": expected a file name");
  std::error_code ec;
  if (fs::is_directory(file, ec)) cannot_write(flag, file, "is a directory, expected a file");
  create_dirs(file.parent_path(), flag);
  const bool existed = fs::exists(file, ec);
  const std::string why = try_open(file);
  if (!existed) fs::remove(file, ec);
  if (!why.empty()) cannot_write(flag, file, "cannot write the file (" + why + ")");
}

}  // namespace bipednav::app
