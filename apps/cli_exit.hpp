#pragma once

#include <nlohmann/json.hpp>
#include <string>

// The exit status of every `bipednav` command (README, "Command line"), in the manner of grep and
// ripgrep: 0 the command did its task, 1 it ran but the task failed (a navigation outcome other
// than SUCCESS, no path, no plane, registration not converged, a benchmark goal missed), 2 an error
// (bad usage, bad input, an unreadable or unwritable file) with the flag or file named.
namespace bipednav::app {

inline constexpr int kExitSuccess = 0;
inline constexpr int kExitTaskFailed = 1;
inline constexpr int kExitError = 2;

// A command whose task can fail reports its verdict here; main() returns task_exit_code() after
// the command (a command that reports nothing succeeded).
void report_task(bool succeeded);
int task_exit_code();
// A benchmark's verdict: every boolean "meets_goal*" key in its JSON object (nested objects and
// arrays included) is true; a null one (a goal not measured in this build) does not count.
bool bench_goals_met(const nlohmann::json& figures);

}  // namespace bipednav::app
