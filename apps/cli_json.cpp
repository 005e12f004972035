#include "apps/cli_json.hpp"

#include <cstdio>
#include <string>

#include "bipednav/common/error.hpp"

namespace bipednav::app {

CLI::Option* add_json_flag(CLI::App* cmd, bool& json) {
  return cmd->add_flag("--json", json, "Print one JSON object with the figures instead of the text");
}

CLI::Option* accept_json_flag(CLI::App* cmd) {
  return cmd->add_flag("--json")->description("Print one JSON object (the only output format)");
}

void print_json(const nlohmann::json& figures) {
  if (!figures.is_object()) throw Error("--json: the command's figures are not one JSON object");
  const std::string text = figures.dump(2);
  std::fwrite(text.data(), 1, text.size(), stdout);
  std::fputc('\n', stdout);
  std::fflush(stdout);
}

void print_figures(bool json, const nlohmann::json& figures, const std::function<void()>& text) {
  if (json)
    print_json(figures);
  else
    text();
}

}  // namespace bipednav::app
