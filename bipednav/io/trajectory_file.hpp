#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "bipednav/common/se3.hpp"

namespace bipednav::io {

// A sequence of poses T_world_frame, with a time stamp each when the file carries them.
struct Trajectory {
  std::vector<SE3> poses;
  std::vector<double> stamps_s;  // one per pose, or empty (KITTI files have none)
};

// Pose files in the two formats odometry benchmarks use:
//   TUM (Sturm et al., IROS 2012):  `t x y z qx qy qz qw` per line, '#' comments;
//   KITTI (Geiger et al., CVPR 2012): 12 numbers per line, the 3x4 matrix [R | t] row-major.
// The reader tells them apart by the number of values on the first pose line (8 or 12). Blank
// lines are skipped. Malformed input throws FileError naming the file and the line: a wrong
// count of values, a value that is not a finite number, a quaternion whose norm is not ~1, or a
// rotation matrix that is not orthonormal within 1e-3.
Trajectory read_trajectory(const std::filesystem::path& file);
Trajectory parse_trajectory(std::string_view text, const std::string& name);

// Writes the poses in TUM format (stamps required, one per pose) or KITTI format, 9 significant
// digits. Throws FileError when the file cannot be written and Error when the sizes differ.
void write_tum_trajectory(const std::filesystem::path& file, const std::vector<double>& stamps_s,
                          const std::vector<SE3>& poses);
void write_kitti_trajectory(const std::filesystem::path& file, const std::vector<SE3>& poses);

namespace detail {
// The lines of a text without their '\n' (the i-th is line i + 1 in messages).
std::vector<std::string_view> text_lines(std::string_view text);
// The whitespace-separated numbers of one text line (line_no counts from 1 for the messages);
// throws FileError on a token that is not a finite number.
std::vector<double> parse_number_line(std::string_view line, const std::string& name, std::size_t line_no);
// v: the 12 values of a KITTI row; throws FileError when the rotation is not orthonormal.
SE3 se3_from_kitti_row(const std::vector<double>& v, const std::string& name, std::size_t line_no);
}  // namespace detail

}  // namespace bipednav::io
