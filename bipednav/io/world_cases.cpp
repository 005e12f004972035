#include "bipednav/io/world_cases.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "bipednav/common/error.hpp"
#include "bipednav/io/number_list.hpp"

namespace bipednav::io {
namespace {

// The shortest text that reads back to the same double.
std::string text_of(double v) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, v).ptr;
  return std::string(text, end);
}

std::string pose_text(const Pose2& p) { return text_of(p.x) + "," + text_of(p.y) + "," + text_of(p.theta); }

class LineParser {
 public:
  LineParser(const std::filesystem::path& file, int line)
      : file_(file.string()), where_("line " + std::to_string(line)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw FileError(file_, where_ + (key.empty() ? "" : " (" + key + ")"), what);
  }
  Pose2 pose(const std::string& key, const std::string& text) const {
    const std::vector<double> v = parse_number_list(text);
    if (v.size() != 2 && v.size() != 3) fail(key, "expected x,y or x,y,yaw (metres, radians), got '" + text + "'");
    return {v[0], v[1], v.size() == 3 ? v[2] : 0.0};
  }
  double positive(const std::string& key, const std::string& text) const {
    const std::vector<double> v = parse_number_list(text);
    if (v.size() != 1 || v[0] <= 0.0) fail(key, "expected a positive number, got '" + text + "'");
    return v[0];
  }
  std::uint64_t whole(const std::string& key, const std::string& text) const {
    std::uint64_t v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc{} || end != text.data() + text.size())
      fail(key, "expected a whole number >= 0, got '" + text + "'");
    return v;
  }
  void tolerance(const std::string& text, WorldCase& c) const {
    const std::vector<double> v = parse_number_list(text);
    if (v.size() != 2 || v[0] <= 0.0 || v[1] <= 0.0)
      fail("tolerance", "expected M,RAD (two positive numbers), got '" + text + "'");
    c.goal_tolerance_m = v[0];
    c.goal_tolerance_rad = v[1];
  }

 private:
  std::string file_, where_;
};

}  // namespace

std::vector<WorldCase> read_world_cases(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw FileError(file.string(), "", "cannot open the cases file");
  std::vector<WorldCase> cases;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::map<std::string, std::string> kv;
    const LineParser p(file, number);
    for (std::string field; fields >> field;) {
      const auto eq = field.find('=');
      if (eq == std::string::npos || eq == 0) p.fail("", "expected key=value, got '" + field + "'");
      if (!kv.emplace(field.substr(0, eq), field.substr(eq + 1)).second) p.fail(field.substr(0, eq), "given twice");
    }
    if (kv.empty()) continue;
    WorldCase c;
    for (const char* required : {"world", "start", "goal"})
      if (!kv.count(required)) p.fail(required, "missing (every case needs world=, start= and goal=)");
    for (const auto& [key, value] : kv) {
      if (key == "world")
        c.world = value;
      else if (key == "start")
        c.start = p.pose(key, value);
      else if (key == "goal")
        c.goal = p.pose(key, value);
      else if (key == "robot")
        c.robot = value;
      else if (key == "tolerance")
        p.tolerance(value, c);
      else if (key == "time_limit")
        c.time_limit_s = p.positive(key, value);
      else if (key == "seed")
        c.seed = p.whole(key, value);
      else if (key == "name")
        c.name = value;
      else
        p.fail(key, "unknown key (expected world, start, goal, robot, tolerance, time_limit, seed or name)");
    }
    if (c.name.empty()) c.name = c.world.stem().string() + "_line" + std::to_string(number);
    cases.push_back(std::move(c));
  }
  if (cases.empty()) throw FileError(file.string(), "", "no cases in the file");
  return cases;
}

void write_world_cases(const std::filesystem::path& file, const std::vector<WorldCase>& cases) {
  std::ofstream out(file);
  if (!out) throw FileError(file.string(), "", "cannot write the cases file");
  out << "# bipednav cases: one per line (world, start, goal as x,y,yaw; tolerance m,rad; time limit s; seed)\n";
  for (const WorldCase& c : cases) {
    out << "name=" << c.name << " world=" << c.world.string() << " start=" << pose_text(c.start)
        << " goal=" << pose_text(c.goal) << " tolerance=" << text_of(c.goal_tolerance_m) << ","
        << text_of(c.goal_tolerance_rad) << " time_limit=" << text_of(c.time_limit_s) << " seed=" << c.seed;
    if (!c.robot.empty()) out << " robot=" << c.robot;
    out << "\n";
  }
  if (!out.flush()) throw FileError(file.string(), "", "cannot write the cases file");
}

}  // namespace bipednav::io
