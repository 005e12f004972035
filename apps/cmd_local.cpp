// `bipednav local plan` (bench/local_drive) and `bipednav bench local` (the harness is bench/local).
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_output.hpp"
#include "apps/cli_pose.hpp"
#include "apps/commands.hpp"
#include "bench/local.hpp"
#include "bench/local_drive.hpp"

namespace bipednav::app {

namespace {

struct PlanOptions {
  std::string map, start, goal, out, planner = "teb";
  int steps = 600;
  int threads = 1;
};

// Drives the robot with the local planner along the global plan; returns whether it reached the goal.
bool local_plan(const PlanOptions& o) {
  bench::LocalDriveOptions d;
  d.map = o.map;
  d.start = parse_pose(o.start, "--start");
  d.goal = parse_pose(o.goal, "--goal");
  if (!o.out.empty()) prepare_output_file(o.out, "--out");
  d.out = o.out;
  d.planner = o.planner;
  d.steps = o.steps;
  d.threads = o.threads;
  const nlohmann::json j = bench::run_local_drive(d);
  print_json(j);
  return j["reached"].get<bool>();
}

// Prints the figures; returns whether the benchmark met its goals (the exit status).
bool bench_local(const bench::LocalBenchOptions& o) {
  const nlohmann::json j = bench::run_local_bench(o);
  print_json(j);
  return bench_goals_met(j);
}

}  // namespace

void add_local_commands(CLI::App& app, CLI::App& bench) {
  CLI::App* local = app.add_subcommand("local", "Local planning (TEB or the path tracker)");
  local->require_subcommand(1);
  auto o = std::make_shared<PlanOptions>();
  CLI::App* plan = local->add_subcommand("plan", "Drive a simulated robot from start to goal on a map_server map");
  plan->add_option("map", o->map, "map_server YAML")->required()->check(CLI::ExistingFile);
  plan->add_option("--start", o->start, "start pose x,y[,yaw]")->required();
  plan->add_option("--goal", o->goal, "goal pose x,y[,yaw]")->required();
  plan->add_option("--out", o->out, "PNG of the map, the global plan, the driven path and the last local trajectory");
  plan->add_option("--planner", o->planner, "teb | tracker")
      ->capture_default_str()
      ->check(CLI::IsMember({"teb", "tracker"}));
  plan->add_option("--steps", o->steps, "maximum control cycles")
      ->capture_default_str()
      ->check(check::integer_at_least(1));
  plan->add_option("--threads", o->threads, "threads for the homotopy candidates")
      ->capture_default_str()
      ->check(check::integer_in(1, 256));
  accept_json_flag(plan);
  plan->callback([o] { report_task(local_plan(*o)); });

  auto* b = bench.add_subcommand("local", "TEB local planner cycle time with 0, 20 and 100 obstacles");
  auto ba = std::make_shared<bench::LocalBenchOptions>();
  b->add_option("--cycles", ba->cycles, "control cycles per obstacle count")
      ->capture_default_str()
      ->check(check::integer_at_least(1));
  b->add_option("--threads", ba->threads, "threads for the homotopy candidates")
      ->capture_default_str()
      ->check(check::integer_in(1, 256));
  accept_json_flag(b);
  b->add_option("--params", ba->params,
                "Navigation parameters YAML: its TEB settings (server.local.teb) over --robot's, as `run --params` "
                "(without --robot: over the TurtleBot3's)");
  b->add_option("--robot", ba->robot,
                "Robot whose TEB settings are measured, as `run` uses them (without --robot and --params: "
                "TebParams' defaults)");
  b->callback([ba] { report_task(bench_local(*ba)); });
}

}  // namespace bipednav::app
