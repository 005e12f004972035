#include <cstdio>
#include <exception>
#include <filesystem>

#include "apps/cli_exit.hpp"
#include "apps/commands.hpp"
#include "bipednav/common/error.hpp"

// Exit status (apps/cli_exit.hpp): 0 success, 1 the task failed, 2 an error.
int main(int argc, char** argv) {
  using namespace bipednav::app;
  CLI::App app{
      "bipednav: autonomous navigation for bipedal and humanoid robots\n"
      "Exit status: 0 success, 1 the task failed (navigation outcome other than SUCCESS, no path, not converged, "
      "benchmark goal missed), 2 bad usage or input"};
  app.require_subcommand(1);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return std::string("bipednav: error: ") + e.what() + "\n(run with --help for the options)\n";
  });
  CLI::App* bench = app.add_subcommand("bench", "Run a benchmark and print its figures");
  bench->require_subcommand(1);

  add_run_commands(app, *bench);
  add_sim_commands(app, *bench);
  add_cloud_commands(app, *bench);
  add_mapping_commands(app, *bench);
  add_plan_commands(app, *bench);
  add_local_commands(app, *bench);
  add_localization_commands(app, *bench);
  add_footstep_commands(app, *bench);
  add_tracking_commands(app, *bench);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are successes; every other parse error is bad usage.
    return app.exit(e) == 0 ? kExitSuccess : kExitError;
  } catch (const bipednav::Error& e) {
    std::fprintf(stderr, "bipednav: error: %s\n", e.what());
    return kExitError;
  } catch (const std::filesystem::filesystem_error& e) {
    std::fprintf(stderr, "bipednav: error: %s\n", e.what());
    return kExitError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bipednav: internal error: %s\n", e.what());
    return kExitError;
  }
  return task_exit_code();
}
