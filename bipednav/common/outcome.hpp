#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace bipednav {

// Outcome codes of Move Base Flex's actions (mbf_msgs GetPath 50-65, ExePath 100-118,
// Recovery 150-158). Planners, controllers and actions all report through these. COLLISION names
// only a contact that happened (the simulator's, a foot landing on an edge); a local planner whose
// best trajectory would enter an obstacle stops with BLOCKED_PATH (ExePath's "path is blocked").
enum class Outcome : std::uint16_t {
  SUCCESS = 0,
  // get_path
  PLAN_FAILURE = 50,
  PLAN_CANCELED = 51,
  INVALID_START = 52,
  INVALID_GOAL = 53,
  BLOCKED_START = 54,
  BLOCKED_GOAL = 55,
  NO_PATH_FOUND = 56,
  PLAN_PAT_EXCEEDED = 57,
  EMPTY_PATH = 58,
  PLAN_TF_ERROR = 59,
  PLAN_NOT_INITIALIZED = 60,
  PLAN_INVALID_PLUGIN = 61,
  PLAN_INTERNAL_ERROR = 62,
  PLAN_OUT_OF_MAP = 63,
  PLAN_MAP_ERROR = 64,
  PLAN_STOPPED = 65,
  // exe_path
  CTRL_FAILURE = 100,
  CTRL_CANCELED = 101,
  NO_VALID_CMD = 102,
  CTRL_PAT_EXCEEDED = 103,
  COLLISION = 104,
  OSCILLATION = 105,
  ROBOT_STUCK = 106,
  MISSED_GOAL = 107,
  MISSED_PATH = 108,
  CTRL_BLOCKED_GOAL = 109,
  BLOCKED_PATH = 110,
  INVALID_PATH = 111,
  CTRL_TF_ERROR = 112,
  CTRL_NOT_INITIALIZED = 113,
  CTRL_INVALID_PLUGIN = 114,
  CTRL_INTERNAL_ERROR = 115,
  CTRL_OUT_OF_MAP = 116,
  CTRL_MAP_ERROR = 117,
  CTRL_STOPPED = 118,
  // recovery
  RECOVERY_FAILURE = 150,
  RECOVERY_CANCELED = 151,
  RECOVERY_PAT_EXCEEDED = 152,
  RECOVERY_TF_ERROR = 153,
  RECOVERY_NOT_INITIALIZED = 154,
  RECOVERY_INVALID_PLUGIN = 155,
  RECOVERY_INTERNAL_ERROR = 156,
  RECOVERY_STOPPED = 157,
  RECOVERY_IMPASSABLE = 158,
};

inline constexpr std::uint16_t code(Outcome o) { return static_cast<std::uint16_t>(o); }

// The mbf_msgs constant name without the action prefix ("NO_PATH_FOUND", "PAT_EXCEEDED", ...).
std::string_view outcome_name(Outcome o);

// An outcome with the human-readable reason that produced it.
struct Result {
  Outcome outcome = Outcome::SUCCESS;
  std::string message;

  bool ok() const { return outcome == Outcome::SUCCESS; }
};

}  // namespace bipednav
