#include "apps/commands.hpp"

namespace bipednav::app {

// Filled in by the module's issue.
void add_local_commands(CLI::App& /*app*/, CLI::App& /*bench*/) {}

}  // namespace bipednav::app
