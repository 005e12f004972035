#include "apps/cli_exit.hpp"

#include <algorithm>

namespace bipednav::app {

namespace {
// One command runs per process; its verdict, read by main() once the command has returned.
int g_task_exit_code = kExitSuccess;
}  // namespace

void report_task(bool succeeded) {
  if (!succeeded) g_task_exit_code = kExitTaskFailed;
}

int task_exit_code() { return g_task_exit_code; }

bool bench_goals_met(const nlohmann::json& figures) {
  if (figures.is_array())
    return std::all_of(figures.begin(), figures.end(), [](const nlohmann::json& e) { return bench_goals_met(e); });
  if (!figures.is_object()) return true;
  for (const auto& [key, value] : figures.items()) {
    if (key.rfind("meets_goal", 0) == 0 && value.is_boolean() && !value.get<bool>()) return false;
    if (!bench_goals_met(value)) return false;
  }
  return true;
}

}  // namespace bipednav::app
