// `bipednav bench worlds`: generated crowd or clutter worlds, or a cases file, with each robot; the
// harness is bench/worlds.
#include "apps/bench_worlds.hpp"

#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "apps/cli_json.hpp"
#include "bench/worlds.hpp"

namespace bipednav::app {
namespace {

struct BenchWorldsArgs {
  bench::WorldBenchOptions options;
  bool json = false;
};

std::string percent(const nlohmann::json& rate) {
  char text[64];
  std::snprintf(text, sizeof text, "%5.1f%% [%4.1f, %5.1f]", 100.0 * rate["ratio"].get<double>(),
                100.0 * rate["ci95"][0].get<double>(), 100.0 * rate["ci95"][1].get<double>());
  return text;
}

void print_table(const nlohmann::json& report) {
  std::printf("%s\n", report["title"].get<std::string>().c_str());
  std::printf("%-12s %5s  %-21s  %-21s  %-21s  %-21s  %s\n", "robot", "runs", "success [95% CI]", "contact, moving",
              "contact, standing", "time-out", "time vs no people");
  for (const nlohmann::json& r : report["robots"]) {
    const nlohmann::json& ratio = r["time_vs_without_people_median_ratio"];
    char time_text[32] = "-";
    if (!ratio.is_null()) std::snprintf(time_text, sizeof time_text, "%.2fx median", ratio.get<double>());
    std::printf("%-12s %5zu  %s  %s  %s  %s  %s\n", r["robot"].get<std::string>().c_str(), r["runs"].get<std::size_t>(),
                percent(r["success"]).c_str(), percent(r["contact_moving"]).c_str(),
                percent(r["contact_standing"]).c_str(), percent(r["timeout"]).c_str(), time_text);
    std::string failures;
    for (const auto& [k, v] : r["failures"].items()) failures += (failures.empty() ? "" : ", ") + k + " " + v.dump();
    std::string layouts;
    for (const auto& [k, v] : r["by_layout"].items())
      layouts += (layouts.empty() ? "" : ", ") + k + " " + v["succeeded"].dump() + "/" + v["runs"].dump();
    std::printf("    by layout: %s; failures: %s%s\n", layouts.c_str(), failures.empty() ? "none" : failures.c_str(),
                r["infeasible"].get<std::size_t>() > 0
                    ? ("; " + r["infeasible"].dump() + " worlds too narrow for it (not run)").c_str()
                    : "");
    if (r["passable"].get<std::size_t>() < r["runs"].get<std::size_t>())
      std::printf("    passable among its people (%zu runs): success %s, contact moving %s, standing %s\n",
                  r["passable"].get<std::size_t>(), percent(r["success_passable"]).c_str(),
                  percent(r["contact_moving_passable"]).c_str(), percent(r["contact_standing_passable"]).c_str());
  }
}

void bench_worlds(const BenchWorldsArgs& a) {
  const nlohmann::json report = bench::run_world_bench(a.options);
  print_figures(a.json, report, [&] { print_table(report); });
}

}  // namespace

void add_world_benches(CLI::App& bench) {
  auto a = std::make_shared<BenchWorldsArgs>();
  CLI::App* w = bench.add_subcommand(
      "worlds", "Generated crowd or clutter worlds (or a cases file) with each robot: success, contacts, time-outs");
  w->add_option("--family", a->options.family, "crowd (people) or clutter (post fields)")
      ->capture_default_str()
      ->check(CLI::IsMember({"crowd", "clutter"}));
  w->add_option("--worlds", a->options.worlds, "Number of generated worlds")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000));
  w->add_option("--first-seed", a->options.first_seed, "The first world's seed: worlds first .. first + N - 1")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000000));
  w->add_option("--robots", a->options.robots, "Robot profiles (names in config/ or profile files)")
      ->capture_default_str();
  w->add_option("--jobs", a->options.jobs, "Runs at a time, each on one thread (results do not depend on it)")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  w->add_option("--cases", a->options.cases,
                "A cases file instead of generated worlds: one case per line, world=FILE start=x,y[,yaw] "
                "goal=x,y[,yaw] [robot=R] [tolerance=M,RAD] [time_limit=S] [seed=K] [name=N]");
  w->add_option("--save-worlds", a->options.save_worlds,
                "Write each generated world as DIR/NAME.world and their cases (with each run's seed) to DIR/cases.txt");
  w->add_option("--params", a->options.params, "Navigation parameters YAML for every run (as `run --params`)");
  w->add_flag("--json", a->json, "Print one JSON object (per robot figures and every run)");
  w->callback([a] { bench_worlds(*a); });
}

}  // namespace bipednav::app
