#include "bipednav/io/trajectory_file.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "bipednav/common/error.hpp"
#include "bipednav/io/pcd.hpp"

namespace bipednav::io {

namespace detail {

std::vector<std::string_view> text_lines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    lines.push_back(text.substr(pos, end - pos));
    pos = end + 1;
  }
  return lines;
}

std::vector<double> parse_number_line(std::string_view line, const std::string& name, std::size_t line_no) {
  std::vector<double> values;
  std::size_t pos = 0;
  while (pos < line.size()) {
    while (pos < line.size() && (line[pos] == ' ' || line[pos] == '\t' || line[pos] == '\r')) ++pos;
    if (pos == line.size()) break;
    std::size_t end = pos;
    while (end < line.size() && line[end] != ' ' && line[end] != '\t' && line[end] != '\r') ++end;
    const std::string_view token = line.substr(pos, end - pos);
    double v = 0.0;
    const char* first = token.data();
    if (!token.empty() && token.front() == '+') ++first;  // from_chars takes no '+'
    const auto [p, ec] = std::from_chars(first, token.data() + token.size(), v);
    if (ec != std::errc() || p != token.data() + token.size() || !std::isfinite(v))
      throw FileError(name, "line " + std::to_string(line_no),
                      "value " + std::to_string(values.size() + 1) + ": expected a finite number, got '" +
                          std::string(token) + "'");
    values.push_back(v);
    pos = end;
  }
  return values;
}

SE3 se3_from_kitti_row(const std::vector<double>& v, const std::string& name, std::size_t line_no) {
  Eigen::Matrix3d R;
  R << v[0], v[1], v[2], v[4], v[5], v[6], v[8], v[9], v[10];
  if (!(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-3) || R.determinant() < 0.0)
    throw FileError(name, "line " + std::to_string(line_no), "the 3x3 rotation is not orthonormal (within 1e-3)");
  // Re-orthonormalised: the files hold 7 significant digits.
  const Eigen::Quaterniond q(R);
  SE3 T = SE3::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(v[3], v[7], v[11]);
  return T;
}

}  // namespace detail

namespace {

SE3 se3_from_tum(const std::vector<double>& v, const std::string& name, std::size_t line_no) {
  Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);  // w, x, y, z
  if (std::abs(q.norm() - 1.0) > 1e-3)
    throw FileError(name, "line " + std::to_string(line_no),
                    "quaternion qx qy qz qw: expected a unit norm, got " + std::to_string(q.norm()));
  SE3 T = SE3::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
  return T;
}

std::ofstream open_for_writing(const std::filesystem::path& file) {
  std::ofstream out(file);
  if (!out) throw FileError(file.string(), "", "cannot open the file for writing");
  return out;
}

}  // namespace

Trajectory parse_trajectory(std::string_view text, const std::string& name) {
  Trajectory t;
  std::size_t columns = 0, line_no = 0;
  for (const std::string_view line : detail::text_lines(text)) {
    ++line_no;
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || line[first] == '#') continue;
    const std::vector<double> v = detail::parse_number_line(line, name, line_no);
    if (columns == 0) {
      if (v.size() != 8 && v.size() != 12)
        throw FileError(name, "line " + std::to_string(line_no),
                        "expected 8 values (TUM: t x y z qx qy qz qw) or 12 (KITTI: a 3x4 matrix), got " +
                            std::to_string(v.size()));
      columns = v.size();
    } else if (v.size() != columns) {
      throw FileError(
          name, "line " + std::to_string(line_no),
          "expected " + std::to_string(columns) + " values like the first pose, got " + std::to_string(v.size()));
    }
    if (columns == 8) {
      t.stamps_s.push_back(v[0]);
      t.poses.push_back(se3_from_tum(v, name, line_no));
    } else {
      t.poses.push_back(detail::se3_from_kitti_row(v, name, line_no));
    }
  }
  if (t.poses.empty()) throw FileError(name, "", "no poses (expected TUM or KITTI pose lines)");
  return t;
}

Trajectory read_trajectory(const std::filesystem::path& file) {
  return parse_trajectory(detail::read_file_bytes(file), file.string());
}

void write_tum_trajectory(const std::filesystem::path& file, const std::vector<double>& stamps_s,
                          const std::vector<SE3>& poses) {
  if (stamps_s.size() != poses.size())
    throw Error("write_tum_trajectory: " + std::to_string(stamps_s.size()) + " stamps for " +
                std::to_string(poses.size()) + " poses");
  std::ofstream out = open_for_writing(file);
  out << "# t x y z qx qy qz qw\n";
  char buf[256];
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Quaterniond q(poses[i].linear());
    const Eigen::Vector3d p = poses[i].translation();
    std::snprintf(buf, sizeof(buf), "%.9f %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", stamps_s[i], p.x(), p.y(), p.z(),
                  q.x(), q.y(), q.z(), q.w());
    out << buf;
  }
  if (!out) throw FileError(file.string(), "", "write failed");
}

void write_kitti_trajectory(const std::filesystem::path& file, const std::vector<SE3>& poses) {
  std::ofstream out = open_for_writing(file);
  char buf[64];
  for (const SE3& T : poses) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) {
        std::snprintf(buf, sizeof(buf), "%s%.9g", r == 0 && c == 0 ? "" : " ", T.matrix()(r, c));
        out << buf;
      }
    out << '\n';
  }
  if (!out) throw FileError(file.string(), "", "write failed");
}

}  // namespace bipednav::io
