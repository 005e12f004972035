#include "bipednav/io/movingai.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "bipednav/common/error.hpp"

namespace bipednav::io {

namespace {

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw FileError(file.string(), "", "cannot open file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Lines without their end-of-line characters (LF or CRLF).
std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
    pos = end + 1;
  }
  return lines;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  for (;;) {
    const std::size_t end = s.find(sep, pos);
    out.push_back(s.substr(pos, end == std::string::npos ? std::string::npos : end - pos));
    if (end == std::string::npos) return out;
    pos = end + 1;
  }
}

std::string where(std::size_t line_index) { return "line " + std::to_string(line_index + 1); }

int parse_int(const std::string& s, const std::string& file, std::size_t line, const std::string& field) {
  int v = 0;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size())
    throw FileError(file, where(line), "field '" + field + "': expected an integer, got '" + s + "'");
  return v;
}

double parse_double(const std::string& s, const std::string& file, std::size_t line, const std::string& field) {
  double v = 0.0;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || p != s.data() + s.size() || !std::isfinite(v) || v < 0.0)
    throw FileError(file, where(line), "field '" + field + "': expected a number >= 0, got '" + s + "'");
  return v;
}

// "key value" header line of a .map file.
int header_value(const std::vector<std::string>& lines, std::size_t i, const std::string& key,
                 const std::string& file) {
  if (i >= lines.size()) throw FileError(file, where(i), "expected '" + key + " N', got end of file");
  const auto parts = split(lines[i], ' ');
  if (parts.size() != 2 || parts[0] != key)
    throw FileError(file, where(i), "expected '" + key + " N', got '" + lines[i] + "'");
  const int v = parse_int(parts[1], file, i, key);
  if (v <= 0) throw FileError(file, where(i), "field '" + key + "': expected a positive integer");
  return v;
}

}  // namespace

bool movingai_passable(char tile) { return tile == '.' || tile == 'G' || tile == 'S'; }

bool MovingAiMap::passable(int x, int y) const { return movingai_passable(tile(x, y)); }

MovingAiMap parse_movingai_map(const std::string& text, const std::string& name) {
  const auto lines = split_lines(text);
  if (lines.empty() || lines[0] != "type octile")
    throw FileError(name, where(0), "field 'type': expected 'type octile'");
  MovingAiMap map;
  map.name = name;
  map.height = header_value(lines, 1, "height", name);
  map.width = header_value(lines, 2, "width", name);
  if (lines.size() < 4 || lines[3] != "map") throw FileError(name, where(3), "expected the line 'map'");
  // The header alone must not size the allocation (a huge width/height fails below instead).
  map.tiles.reserve(std::min(static_cast<std::size_t>(map.width) * map.height, text.size()));
  for (int y = 0; y < map.height; ++y) {
    const std::size_t li = 4 + static_cast<std::size_t>(y);
    if (li >= lines.size())
      throw FileError(
          name, where(li),
          "map row " + std::to_string(y) + ": expected " + std::to_string(map.height) + " rows, got end of file");
    if (static_cast<int>(lines[li].size()) != map.width)
      throw FileError(name, where(li),
                      "map row " + std::to_string(y) + ": expected " + std::to_string(map.width) + " tiles, got " +
                          std::to_string(lines[li].size()));
    map.tiles.insert(map.tiles.end(), lines[li].begin(), lines[li].end());
  }
  for (std::size_t li = 4 + map.height; li < lines.size(); ++li)
    if (!lines[li].empty()) throw FileError(name, where(li), "unexpected text after the last map row");
  return map;
}

std::vector<MovingAiProblem> parse_movingai_scen(const std::string& text, const std::string& name) {
  const auto lines = split_lines(text);
  if (lines.empty() || (lines[0] != "version 1" && lines[0] != "version 1.0"))
    throw FileError(name, where(0), "field 'version': expected 'version 1'");
  static const char* const kFields[] = {"bucket",  "map",    "map_width", "map_height",    "start_x",
                                        "start_y", "goal_x", "goal_y",    "optimal_length"};
  std::vector<MovingAiProblem> out;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].empty()) continue;
    const auto f = split(lines[i], '\t');
    if (f.size() != 9)
      throw FileError(name, where(i), "expected 9 TAB-separated fields, got " + std::to_string(f.size()));
    MovingAiProblem p;
    p.bucket = parse_int(f[0], name, i, kFields[0]);
    p.map = f[1];
    p.map_width = parse_int(f[2], name, i, kFields[2]);
    p.map_height = parse_int(f[3], name, i, kFields[3]);
    p.start_x = parse_int(f[4], name, i, kFields[4]);
    p.start_y = parse_int(f[5], name, i, kFields[5]);
    p.goal_x = parse_int(f[6], name, i, kFields[6]);
    p.goal_y = parse_int(f[7], name, i, kFields[7]);
    p.optimal_length = parse_double(f[8], name, i, kFields[8]);
    const int xs[] = {p.start_x, p.goal_x}, ys[] = {p.start_y, p.goal_y};
    for (int k = 0; k < 2; ++k) {
      if (xs[k] < 0 || xs[k] >= p.map_width)
        throw FileError(name, where(i), std::string("field '") + kFields[4 + 2 * k] + "': outside the map width");
      if (ys[k] < 0 || ys[k] >= p.map_height)
        throw FileError(name, where(i), std::string("field '") + kFields[5 + 2 * k] + "': outside the map height");
    }
    out.push_back(std::move(p));
  }
  return out;
}

MovingAiMap read_movingai_map(const std::filesystem::path& file) {
  return parse_movingai_map(read_text(file), file.string());
}

std::vector<MovingAiProblem> read_movingai_scen(const std::filesystem::path& file) {
  return parse_movingai_scen(read_text(file), file.string());
}

}  // namespace bipednav::io
