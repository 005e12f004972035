#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <nlohmann/json.hpp>

// `--json`, the same on every command that prints figures (README, "Command line"): with it the
// command prints exactly one JSON object on stdout, with the figures its text gives (units in the
// key names: `_m`, `_s`, `_ms`, `_rad`), and nothing else there; notes go to stderr.
namespace bipednav::app {

// Adds `--json` to `cmd`, setting `json`.
CLI::Option* add_json_flag(CLI::App* cmd, bool& json);
// Adds `--json` to a command that prints its JSON object either way (benchmarks, `costmap`,
// `local plan`): accepted, so that scripts can pass it to every command, and bound to nothing.
CLI::Option* accept_json_flag(CLI::App* cmd);

// Prints `figures` on stdout as the command's one JSON object (throws Error when it is not an object).
void print_json(const nlohmann::json& figures);

// With --json, print_json(figures); otherwise `text()` prints the same figures for a person.
void print_figures(bool json, const nlohmann::json& figures, const std::function<void()>& text);

}  // namespace bipednav::app
