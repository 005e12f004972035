#include "apps/cmd_route.hpp"

#include <cstdio>
#include <memory>
#include <string>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_world.hpp"
#include "bench/json_figures.hpp"
#include "bench/route_report.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/footstep_runner.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/placement_check.hpp"
#include "bipednav/sim/scenario_files.hpp"
#include "bipednav/sim/space_time_route.hpp"

namespace bipednav::app {

namespace {

struct RouteArgs {
  std::string scenario;
  std::string world, start, goal;  // instead of a scenario
  std::string robot;               // empty: the scenario's
  double resolution_m = 0.01;
  bool json = false;
};

void print_report(const nlohmann::json& r) {
  std::printf("%s with %s: needs %.3f m from its centre to any obstacle (footprint + sway)\n",
              r["scenario"].get<std::string>().c_str(), r["robot"].get<std::string>().c_str(),
              r["needed_m"].get<double>());
  for (const auto& g : r["routes"]) {
    const auto& goal = g["goal"];
    std::printf("  to goal (%.2f, %.2f): ", goal[0].get<double>(), goal[1].get<double>());
    if (!g["connected"].get<bool>()) {
      std::printf("no route (start or goal inside an obstacle or outside the bounds, or walled off)\n");
    } else if (g["widest_m"].is_null()) {
      std::printf("no obstacles\n");
    } else {
      const auto& b = g["bottleneck"];
      std::printf("widest route keeps %.3f m, narrowest at (%.2f, %.2f) next to %s: margin %+.3f m\n",
                  g["widest_m"].get<double>(), b[0].get<double>(), b[1].get<double>(),
                  g["bottleneck_obstacle"].get<std::string>().c_str(), g["margin_m"].get<double>());
    }
  }
}

// The space-time answer among the scenario's people (sim/space_time_route.hpp).
void print_people(const nlohmann::json& p) {
  if (p["passable"].get<bool>())
    std::printf("  among its people: passable for a robot that knew their walks, at %.1f s (%.1f s without them)\n",
                p["arrival_s"].get<double>(), p["static_arrival_s"].get<double>());
  else
    std::printf("  among its people: not passable within %.1f s, even for a robot that knew their walks\n",
                p["time_limit_s"].get<double>());
}

// Whether every goal has a route with room for the robot (the exit status: 0, else 1).
bool every_route_has_room(const nlohmann::json& r) {
  for (const auto& g : r["routes"])
    if (!g["connected"].get<bool>() || (!g["margin_m"].is_null() && g["margin_m"].get<double>() < 0.0)) return false;
  return true;
}

bool run_route(const RouteArgs& a) {
  if (a.world.empty() && a.scenario.empty()) throw Error("route needs a SCENARIO or --world FILE");
  const sim::Scenario s = a.world.empty() ? sim::load_scenario(sim::resolve_scenario(a.scenario))
                                          : scenario_from_world(a.world, a.robot, a.start, a.goal);
  const RobotProfile robot = navigation::load_robot(a.robot.empty() ? s.robot : a.robot);
  nlohmann::json r = bench::route_report(s, robot, a.resolution_m);
  if (!s.world.actors.empty()) {
    const sim::SpaceTimeRoute p = sim::scenario_space_time_route(s, robot);
    r["people"] = {{"passable", p.reachable},
                   {"arrival_s", bench::finite_or_null(p.arrival_s)},
                   {"static_arrival_s", bench::finite_or_null(p.static_arrival_s)},
                   {"time_limit_s", s.time_limit_s}};
  }
  print_figures(a.json, r, [&] {
    print_report(r);
    if (r.contains("people")) print_people(r["people"]);
    try {  // why a route is missing: a start or goal in an obstacle or off the map
      sim::check_placements(s, robot, !runner::is_footstep_robot(robot));
    } catch (const Error& e) {
      std::printf("  %s\n", e.what());
    }
  });
  return every_route_has_room(r);
}

}  // namespace

void add_route_command(CLI::App& app) {
  auto a = std::make_shared<RouteArgs>();
  CLI::App* cmd = app.add_subcommand(
      "route",
      "The widest route of a scenario's static world from the start to each goal (ground truth, before any "
      "sensing), against the room the robot needs: can it get there at all, and with what margin");
  CLI::Option* scenario = cmd->add_option("scenario", a->scenario, "Scenario name (scenarios/NAME.yaml) or file");
  add_world_options(cmd, scenario, a->world, a->start, a->goal);
  cmd->add_option("--robot", a->robot, "Robot profile (name in config/ or a file); default: the scenario's");
  cmd->add_option("--resolution", a->resolution_m, "Grid of route centre positions, m")
      ->capture_default_str()
      ->check(check::in_range(0.001, 1.0));
  add_json_flag(cmd, a->json);
  cmd->callback([a] { report_task(run_route(*a)); });
}

}  // namespace bipednav::app
