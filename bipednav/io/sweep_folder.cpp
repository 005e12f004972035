#include "bipednav/io/sweep_folder.hpp"

#include <algorithm>
#include <cctype>

#include "bipednav/common/error.hpp"
#include "bipednav/io/kitti_sequence.hpp"
#include "bipednav/io/pcd.hpp"
#include "bipednav/io/ply.hpp"

namespace bipednav::io {

namespace fs = std::filesystem;

std::string to_string(SweepFormat f) {
  switch (f) {
    case SweepFormat::kitti:
      return "kitti";
    case SweepFormat::pcd:
      return "pcd";
    case SweepFormat::ply:
      return "ply";
    case SweepFormat::rosbag:
      return "rosbag";
  }
  return "?";
}

SweepFormat sweep_format_from_string(const std::string& s) {
  for (const SweepFormat f : {SweepFormat::kitti, SweepFormat::pcd, SweepFormat::ply, SweepFormat::rosbag})
    if (to_string(f) == s) return f;
  throw Error("unknown sweep format '" + s + "' (expected kitti, pcd, ply or rosbag)");
}

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Natural order: digit runs compare by value (then by length, so 02 and 2 keep a fixed order).
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && digit(a[ie])) ++ie;
      while (je < b.size() && digit(b[je])) ++je;
      std::size_t ia = i, jb = j;  // skip leading zeros
      while (ia + 1 < ie && a[ia] == '0') ++ia;
      while (jb + 1 < je && b[jb] == '0') ++jb;
      if (ie - ia != je - jb) return ie - ia < je - jb;
      const int c = a.compare(ia, ie - ia, b, jb, je - jb);
      if (c != 0) return c < 0;
      if (ie - i != je - j) return ie - i < je - j;
      i = ie;
      j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

}  // namespace

std::vector<fs::path> list_sweep_files(const fs::path& dir, const std::string& ext) {
  std::vector<fs::path> out;
  if (!fs::is_directory(dir)) return out;
  const std::string want = lower(ext);
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && lower(e.path().extension().string()) == want) out.push_back(e.path());
  std::sort(out.begin(), out.end(), [](const fs::path& a, const fs::path& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  return out;
}

SweepFormat detect_sweep_format(const fs::path& path) {
  if (fs::is_regular_file(path) && lower(path.extension().string()) == ".bag") return SweepFormat::rosbag;
  if (!fs::is_directory(path))
    throw FileError(path.string(), "", "expected a folder of sweeps (KITTI, PCD or PLY) or a .bag file");
  if (is_kitti_sequence(path)) return SweepFormat::kitti;
  if (!list_sweep_files(path, ".pcd").empty()) return SweepFormat::pcd;
  if (!list_sweep_files(path, ".ply").empty()) return SweepFormat::ply;
  throw FileError(path.string(), "", "no sweeps found (expected velodyne/*.bin, *.bin, *.pcd or *.ply)");
}

SweepFiles open_sweep_files(const fs::path& path, SweepFormat format) {
  SweepFiles s;
  s.format = format;
  switch (format) {
    case SweepFormat::kitti: {
      KittiSequence k = open_kitti_sequence(path);
      s.files = std::move(k.sweeps);
      s.T_lidar0_lidar = std::move(k.T_lidar0_lidar);
      return s;
    }
    case SweepFormat::pcd:
    case SweepFormat::ply: {
      const std::string name = to_string(format);
      s.files = list_sweep_files(path, std::string(".").append(name));
      if (s.files.empty())
        throw FileError(path.string(), "", std::string("no *.").append(name).append(" sweeps in this folder"));
      return s;
    }
    case SweepFormat::rosbag:
      break;
  }
  throw Error("open_sweep_files: a rosbag is one file, not a folder of sweeps");
}

PointCloud read_sweep(const SweepFiles& files, std::size_t i) {
  const fs::path& f = files.files.at(i);
  switch (files.format) {
    case SweepFormat::kitti:
      return read_kitti_sweep(f);
    case SweepFormat::pcd:
      return read_pcd(f);
    case SweepFormat::ply:
      return read_ply(f);
    case SweepFormat::rosbag:
      break;
  }
  throw Error("read_sweep: a rosbag is not a folder of sweeps");
}

}  // namespace bipednav::io
