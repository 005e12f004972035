#include "bipednav/common/outcome.hpp"

namespace bipednav {

std::string_view outcome_name(Outcome o) {
  switch (o) {
    case Outcome::SUCCESS:
      return "SUCCESS";
    case Outcome::PLAN_FAILURE:
    case Outcome::CTRL_FAILURE:
    case Outcome::RECOVERY_FAILURE:
      return "FAILURE";
    case Outcome::PLAN_CANCELED:
    case Outcome::CTRL_CANCELED:
    case Outcome::RECOVERY_CANCELED:
      return "CANCELED";
    case Outcome::INVALID_START:
      return "INVALID_START";
    case Outcome::INVALID_GOAL:
      return "INVALID_GOAL";
    case Outcome::BLOCKED_START:
      return "BLOCKED_START";
    case Outcome::BLOCKED_GOAL:
    case Outcome::CTRL_BLOCKED_GOAL:
      return "BLOCKED_GOAL";
    case Outcome::NO_PATH_FOUND:
      return "NO_PATH_FOUND";
    case Outcome::PLAN_PAT_EXCEEDED:
    case Outcome::CTRL_PAT_EXCEEDED:
    case Outcome::RECOVERY_PAT_EXCEEDED:
      return "PAT_EXCEEDED";
    case Outcome::EMPTY_PATH:
      return "EMPTY_PATH";
    case Outcome::PLAN_TF_ERROR:
    case Outcome::CTRL_TF_ERROR:
    case Outcome::RECOVERY_TF_ERROR:
      return "TF_ERROR";
    case Outcome::PLAN_NOT_INITIALIZED:
    case Outcome::CTRL_NOT_INITIALIZED:
    case Outcome::RECOVERY_NOT_INITIALIZED:
      return "NOT_INITIALIZED";
    case Outcome::PLAN_INVALID_PLUGIN:
    case Outcome::CTRL_INVALID_PLUGIN:
    case Outcome::RECOVERY_INVALID_PLUGIN:
      return "INVALID_PLUGIN";
    case Outcome::PLAN_INTERNAL_ERROR:
    case Outcome::CTRL_INTERNAL_ERROR:
    case Outcome::RECOVERY_INTERNAL_ERROR:
      return "INTERNAL_ERROR";
    case Outcome::PLAN_OUT_OF_MAP:
    case Outcome::CTRL_OUT_OF_MAP:
      return "OUT_OF_MAP";
    case Outcome::PLAN_MAP_ERROR:
    case Outcome::CTRL_MAP_ERROR:
      return "MAP_ERROR";
    case Outcome::PLAN_STOPPED:
    case Outcome::CTRL_STOPPED:
    case Outcome::RECOVERY_STOPPED:
      return "STOPPED";
    case Outcome::NO_VALID_CMD:
      return "NO_VALID_CMD";
    case Outcome::COLLISION:
      return "COLLISION";
    case Outcome::OSCILLATION:
      return "OSCILLATION";
    case Outcome::ROBOT_STUCK:
      return "ROBOT_STUCK";
    case Outcome::MISSED_GOAL:
      return "MISSED_GOAL";
    case Outcome::MISSED_PATH:
      return "MISSED_PATH";
    case Outcome::BLOCKED_PATH:
      return "BLOCKED_PATH";
    case Outcome::INVALID_PATH:
      return "INVALID_PATH";
    case Outcome::RECOVERY_IMPASSABLE:
      return "IMPASSABLE";
  }
  return "UNKNOWN";
}

}  // namespace bipednav
