#include <cstdio>
#include <exception>

#include "apps/commands.hpp"
#include "bipednav/common/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{"bipednav: autonomous navigation for bipedal and humanoid robots"};
  app.require_subcommand(1);
  CLI::App* bench = app.add_subcommand("bench", "Run a benchmark and print its figures");
  bench->require_subcommand(1);

  using namespace bipednav::app;
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
    return app.exit(e);
  } catch (const bipednav::Error& e) {
    std::fprintf(stderr, "bipednav: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bipednav: internal error: %s\n", e.what());
    return 2;
  }
  return 0;
}
