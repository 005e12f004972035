// `bipednav bench tracking --json`: the multi-object tracker's accuracy against the simulator's
// ground truth over closed-loop runs of the navigator; the harness is bench/tracking.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/cli_json.hpp"
#include "apps/commands.hpp"
#include "bench/tracking.hpp"
#include "bench/tracking_harness.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/io/param_overlay.hpp"
#include "bipednav/sim/scenario_files.hpp"
#include "bipednav/sim/world_generator.hpp"

namespace bipednav::app {

namespace {

struct BenchTrackingArgs {
  std::vector<std::string> scenarios{"hexagon_dynamic", "three_rooms", "digit_lab_dynamic"};
  std::vector<std::string> robots{"turtlebot3", "digit"};
  int seeds = 1;
  int first_seed = 1;
  int crowd_worlds = 0;  // generated crowd worlds scored after the scenarios (`bench worlds`' family)
  int first_world = 1;
  std::vector<std::string> variants;  // NAME:key=value,... (beyond the two default trackers)
  bool json = false;
};

// The trackers under test: the constant-velocity and IMM filters with their defaults, then each
// --variant NAME:key=value,... (the defaults changed by its settings).
std::vector<bench::TrackerVariant> tracker_variants(const std::vector<std::string>& specs) {
  std::vector<bench::TrackerVariant> out{{"kalman_cv", {}}, {"kalman_imm_cv_ct", {}}};
  out[1].params.motion_model = "imm";
  for (const auto& spec : specs) {
    const auto colon = spec.find(':');
    bench::TrackerVariant v{spec.substr(0, colon), {}};
    if (v.name.empty() || colon == std::string::npos)
      throw CLI::ValidationError("--variant", "expected NAME:key=value[,key=value...], got '" + spec + "'");
    // The settings as a YAML mapping, read as a parameters file reads TrackerParams' fields.
    std::string yaml;
    std::size_t at = colon + 1;
    while (at < spec.size()) {
      const auto comma = std::min(spec.find(',', at), spec.size());
      const std::string item = spec.substr(at, comma - at);
      const auto eq = item.find('=');
      if (eq == std::string::npos) throw CLI::ValidationError("--variant", "expected key=value, got '" + item + "'");
      yaml += item.substr(0, eq) + ": " + item.substr(eq + 1) + "\n";
      at = comma + 1;
    }
    try {
      io::ParamReader r = io::ParamReader::from_string(yaml, "variant " + v.name);
      io::overlay_fields(r, v.params);
      v.params.validate();
    } catch (const Error& e) {  // an unknown key, a value of the wrong type or out of range
      throw CLI::ValidationError("--variant", e.what());
    }
    out.push_back(v);
  }
  return out;
}

void print_table(const nlohmann::json& pooled) {
  std::printf("%-34s %9s %9s %7s %6s %6s %6s %6s %9s\n", "tracker", "pos RMSE", "vel RMSE", "MOTA", "FN", "FP", "IDSW",
              "GT", "confirm");
  for (const auto& [name, j] : pooled.items()) {
    std::printf("%-34s %7.3f m %5.3f m/s %7.3f %6ld %6ld %6ld %6ld %7.2f s\n", name.c_str(),
                j["position_rmse_m"].get<double>(), j["velocity_rmse_mps"].get<double>(), j["mota_ratio"].get<double>(),
                j["misses"].get<long>(), j["false_positives"].get<long>(), j["id_switches"].get<long>(),
                j["truths"].get<long>(), j["mean_time_to_confirm_s"].get<double>());
  }
}

}  // namespace

void add_tracking_commands(CLI::App& /*app*/, CLI::App& bench) {
  auto a = std::make_shared<BenchTrackingArgs>();
  CLI::App* b = bench.add_subcommand(
      "tracking", "Multi-object tracking accuracy against the simulator's actors (CLEAR MOT, RMSE) in closed loops");
  CLI::Option* scen =
      b->add_option("--scenarios", a->scenarios, "Scenario names or files (none by default with --crowd-worlds)")
          ->capture_default_str();
  b->add_option("--robots", a->robots, "Robot profiles (names in config/ or profile files)")->capture_default_str();
  b->add_option("--seeds", a->seeds, "Seeds per scenario and robot")->capture_default_str()->check(CLI::Range(1, 1000));
  b->add_option("--first-seed", a->first_seed, "The first seed: runs seeds first .. first + N - 1")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000000));
  b->add_option("--crowd-worlds", a->crowd_worlds,
                "Generated crowd worlds (as `bench worlds --family crowd`) scored after the scenarios")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  b->add_option("--first-world", a->first_world, "The first crowd world's seed: worlds first .. first + N - 1")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000000));
  b->add_option("--variant", a->variants,
                "A further tracker: NAME:key=value[,key=value...] over the defaults (TrackerParams fields)");
  b->add_flag("--json", a->json, "Print one JSON object (pooled scores and every run's)");
  b->callback([a, scen] {
    if (a->crowd_worlds > 0 && scen->count() == 0) a->scenarios.clear();
    const std::vector<bench::TrackerVariant> variants = tracker_variants(a->variants);
    if ((a->scenarios.empty() && a->crowd_worlds == 0) || a->robots.empty())
      throw CLI::ValidationError("--scenarios/--crowd-worlds/--robots", "a scenario or a crowd world, and a robot");
    std::vector<sim::Scenario> scenarios;
    for (const auto& name : a->scenarios) scenarios.push_back(sim::load_scenario(sim::resolve_scenario(name)));
    for (int i = 0; i < a->crowd_worlds; ++i)
      scenarios.push_back(
          sim::generate_world(sim::WorldFamily::crowd, static_cast<std::uint64_t>(a->first_world + i)).scenario);
    std::vector<std::uint64_t> seeds;
    for (int i = 0; i < a->seeds; ++i) seeds.push_back(static_cast<std::uint64_t>(a->first_seed + i));
    const nlohmann::json j = bench::bench_tracking(scenarios, a->robots, seeds, variants, !a->json);
    print_figures(a->json, j, [&] { print_table(j["trackers"]); });
  });
}

}  // namespace bipednav::app
