#include "bipednav/sim/fault.hpp"

#include <array>
#include <cmath>
#include <sstream>

#include "bipednav/common/error.hpp"
#include "bipednav/io/param_reader.hpp"

namespace bipednav::sim {
namespace {

constexpr std::array<std::pair<FaultType, const char*>, 8> kNames{{
    {FaultType::LIDAR_DROPOUT, "lidar_dropout"},
    {FaultType::DEPTH_NAN_BURST, "depth_nan_burst"},
    {FaultType::LOCALIZATION_JUMP, "localization_jump"},
    {FaultType::ODOMETRY_SLIP, "odometry_slip"},
    {FaultType::STALE_TIMESTAMPS, "stale_timestamps"},
    {FaultType::OUT_OF_ORDER_TIMESTAMPS, "out_of_order_timestamps"},
    {FaultType::GOAL_FLOOD, "goal_flood"},
    {FaultType::COMMAND_DROPOUT, "command_dropout"},
}};

std::vector<double> split_numbers(const std::string& text, char sep, const std::string& what) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, sep)) {
    try {
      std::size_t used = 0;
      out.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw Error("--fault '" + what + "': '" + item + "' is not a number");
    }
  }
  return out;
}

}  // namespace

FaultType fault_type_from_name(const std::string& name) {
  std::string known;
  for (const auto& [type, n] : kNames) {
    if (name == n) return type;
    known += (known.empty() ? "" : ", ") + std::string(n);
  }
  throw Error("unknown fault type '" + name + "' (known: " + known + ")");
}

void Fault::validate() const {
  require(std::isfinite(start_s) && start_s >= 0.0, "fault.start_s", "a finite time >= 0");
  require(std::isfinite(duration_s) && duration_s > 0.0, "fault.duration_s", "a finite duration > 0");
  require(nan_fraction >= 0.0 && nan_fraction <= 1.0, "fault.nan_fraction", "in [0, 1]");
  require(jump.is_finite(), "fault.jump", "[dx, dy, dyaw] finite");
  require(std::isfinite(slip_scale) && slip_scale >= 0.0 && slip_scale <= 10.0, "fault.slip_scale", "in [0, 10]");
  require(std::isfinite(delay_s) && delay_s > 0.0, "fault.delay_s", "a finite delay > 0");
  require(goal_count >= 1 && goal_count <= 10000, "fault.goal_count", "in [1, 10000]");
}

Fault read_fault(io::ParamReader& r) {
  Fault f;
  std::string type;
  r.require("type", type);
  try {
    f.type = fault_type_from_name(type);
  } catch (const Error& e) {
    r.fail("type", e.what());
  }
  r.require("start_s", f.start_s);
  r.get("duration_s", f.duration_s);
  r.get("nan_fraction", f.nan_fraction);
  r.get("slip_scale", f.slip_scale);
  r.get("delay_s", f.delay_s);
  r.get("goal_count", f.goal_count);
  std::vector<double> j;
  if (r.get("jump", j)) {
    if (j.size() != 3) r.fail("jump", "[dx, dy, dyaw] (m, m, rad)");
    f.jump = {j[0], j[1], j[2]};
  }
  r.finish();
  try {
    f.validate();
  } catch (const ParamError& e) {
    r.fail(type, e.what());
  }
  return f;
}

Fault parse_fault(const std::string& spec) {
  std::vector<std::string> parts;
  std::stringstream ss(spec);
  std::string item;
  while (std::getline(ss, item, ':')) parts.push_back(item);
  if (parts.size() < 3 || parts.size() > 4)
    throw Error("--fault '" + spec + "': expected type:start_s:duration_s[:value]");
  Fault f;
  f.type = fault_type_from_name(parts[0]);
  f.start_s = split_numbers(parts[1], ',', spec).at(0);
  f.duration_s = split_numbers(parts[2], ',', spec).at(0);
  if (parts.size() == 4) {
    const std::vector<double> v = split_numbers(parts[3], ',', spec);
    const bool is_jump = f.type == FaultType::LOCALIZATION_JUMP;
    if (v.size() != (is_jump ? 3u : 1u)) throw Error("--fault '" + spec + "': wrong number of values");
    switch (f.type) {
      case FaultType::DEPTH_NAN_BURST:
        f.nan_fraction = v[0];
        break;
      case FaultType::LOCALIZATION_JUMP:
        f.jump = {v[0], v[1], v[2]};
        break;
      case FaultType::ODOMETRY_SLIP:
        f.slip_scale = v[0];
        break;
      case FaultType::STALE_TIMESTAMPS:
        f.delay_s = v[0];
        break;
      case FaultType::GOAL_FLOOD:
        f.goal_count = static_cast<int>(v[0]);
        break;
      default:
        throw Error("--fault '" + spec + "': " + parts[0] + " takes no value");
    }
  }
  try {
    f.validate();
  } catch (const ParamError& e) {
    throw Error("--fault '" + spec + "': " + e.what());
  }
  return f;
}

}  // namespace bipednav::sim
