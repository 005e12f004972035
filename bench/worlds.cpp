#include "bench/worlds.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "bench/bench_runs.hpp"
#include "bench/json_figures.hpp"
#include "bench/route_report.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/common/wilson_interval.hpp"
#include "bipednav/io/world_cases.hpp"
#include "bipednav/sim/scenario_files.hpp"
#include "bipednav/sim/sdf_writer.hpp"
#include "bipednav/sim/space_time_route.hpp"
#include "bipednav/sim/world_generator.hpp"

namespace bipednav::bench {
namespace {

namespace fs = std::filesystem;

// A world of the bench: generated (with its layout), or a case of the cases file.
struct BenchWorld {
  sim::Scenario scenario;
  std::string layout;  // corridor | doorway | hall | clutter | case
  std::string robot;   // a case's own robot (empty: every robot of the bench)
};

// One run: a world with a robot, with its people or (baseline) without.
struct WorldRun {
  std::size_t world = 0;
  std::string robot;
  bool baseline = false;
  nlohmann::json margin_m;  // the static route's margin for this robot (null: no obstacles)
  bool feasible = true;     // the margin is positive: the robot fits through at all
  // With people: whether a robot of this size and top speed that knew the people's walks could
  // reach the goal untouched (sim/space_time_route.hpp); unset without people.
  std::optional<sim::SpaceTimeRoute> passable;
  runner::RunResult result;
  std::string error;  // what a run that threw said (it counts as failed)
};

std::vector<BenchWorld> generated_worlds(const WorldBenchOptions& a) {
  const sim::WorldFamily family = sim::parse_world_family(a.family);
  std::vector<BenchWorld> worlds;
  for (int i = 0; i < a.worlds; ++i) {
    sim::GeneratedWorld g = sim::generate_world(family, static_cast<std::uint64_t>(a.first_seed + i));
    worlds.push_back({std::move(g.scenario), g.layout, ""});
  }
  return worlds;
}

std::vector<BenchWorld> case_worlds(const std::string& cases_file) {
  std::vector<BenchWorld> worlds;
  const fs::path dir = fs::path(cases_file).parent_path();
  for (const io::WorldCase& c : io::read_world_cases(cases_file)) {
    const fs::path world = c.world.is_absolute() ? c.world : dir / c.world;
    sim::Scenario s = sim::scenario_from_world(world, c.robot, c.start, c.goal);
    s.name = c.name;
    s.goal_tolerance_m = c.goal_tolerance_m;
    s.goal_tolerance_rad = c.goal_tolerance_rad;
    s.time_limit_s = c.time_limit_s;
    s.seed = c.seed;
    worlds.push_back({std::move(s), "case", c.robot});
  }
  return worlds;
}

// Each generated world as DIR/NAME.world, and DIR/cases.txt to run them again with their seeds
// (`--cases`, or one by one with `run --world ... --seed N`).
void save_worlds(const std::vector<BenchWorld>& worlds, const fs::path& dir) {
  fs::create_directories(dir);
  std::vector<io::WorldCase> cases;
  for (const BenchWorld& w : worlds) {
    const sim::Scenario& s = w.scenario;
    sim::write_sdf_world(s.world, dir / (s.name + ".world"));
    cases.push_back({s.name, s.name + ".world", "", s.start, s.goals.back().pose, s.goal_tolerance_m,
                     s.goal_tolerance_rad, s.time_limit_s, s.seed});
  }
  io::write_world_cases(dir / "cases.txt", cases);
}

std::vector<WorldRun> plan_runs(const std::vector<BenchWorld>& worlds, const std::vector<std::string>& robots) {
  std::vector<WorldRun> runs;
  for (std::size_t k = 0; k < worlds.size(); ++k) {
    const std::vector<std::string> who = worlds[k].robot.empty() ? robots : std::vector{worlds[k].robot};
    for (const std::string& robot : who) {
      for (const bool baseline : {false, true}) {
        if (baseline && worlds[k].scenario.world.actors.empty()) continue;
        WorldRun& r = runs.emplace_back();
        r.world = k;
        r.robot = robot;
        r.baseline = baseline;
      }
    }
  }
  return runs;
}

void run_world(WorldRun& r, const BenchWorld& w, const RobotProfile& profile, const runner::RunOptions& base) {
  try {
    constexpr double kRouteResolutionM = 0.02;
    r.margin_m = route_report(w.scenario, profile, kRouteResolutionM)["min_margin_m"];
    r.feasible = r.margin_m.is_null() || r.margin_m.get<double>() > 0.0;
    if (!r.feasible) return;
    if (!r.baseline && !w.scenario.world.actors.empty())
      r.passable = sim::scenario_space_time_route(w.scenario, profile);
    runner::RunOptions o = base;
    o.robot = r.robot;
    r.result = runner::run_scenario(r.baseline ? sim::without_people(w.scenario) : w.scenario, o);
  } catch (const std::exception& e) {
    r.error = e.what();
  }
}

nlohmann::json rate(std::size_t k, std::size_t n) {
  const Interval ci = wilson_interval(k, n);
  return {
      {"count", k}, {"ratio", n > 0 ? static_cast<double>(k) / static_cast<double>(n) : 0.0}, {"ci95", {ci.lo, ci.hi}}};
}

nlohmann::json run_row(const WorldRun& r, const BenchWorld& w, const WorldRun* baseline) {
  nlohmann::json j{{"world", w.scenario.name}, {"seed", w.scenario.seed},      {"layout", w.layout},
                   {"robot", r.robot},         {"route_margin_m", r.margin_m}, {"feasible", r.feasible}};
  if (!r.error.empty()) j["error"] = r.error;
  if (r.passable) {
    j["passable"] = r.passable->reachable;
    j["passable_arrival_s"] = finite_or_null(r.passable->arrival_s);
    j["static_arrival_s"] = finite_or_null(r.passable->static_arrival_s);
  }
  if (!r.feasible || !r.error.empty()) return j;
  const runner::RunResult& x = r.result;
  j["success"] = x.success;
  j["verdict"] = x.verdict;
  j["navigator_outcome"] = std::string(outcome_name(x.outcome.outcome));
  j["timeout"] = x.outcome.outcome == Outcome::CTRL_PAT_EXCEEDED;
  j["time_s"] = x.time_s;
  j["min_clearance_m"] = x.min_clearance_m;
  j["localization_error_m"] = x.localization_error_m;
  if (x.first_collision)
    j["contact"] = {{"obstacle", x.first_collision->obstacle},
                    {"time_s", x.first_collision->time_s},
                    {"robot_standing", sim::robot_standing(*x.first_collision)}};
  if (baseline && baseline->error.empty()) {
    j["without_people_success"] = baseline->result.success;
    j["without_people_time_s"] = baseline->result.time_s;
  }
  return j;
}

// One robot's figures over its runs with people (`rows` of that robot).
nlohmann::json robot_summary(const std::string& robot, const std::vector<nlohmann::json>& rows) {
  std::size_t n = 0, ok = 0, moving = 0, standing = 0, people = 0, timeouts = 0, false_success = 0, infeasible = 0;
  std::size_t passable = 0, passable_ok = 0, passable_moving = 0, passable_standing = 0;
  std::map<std::string, std::size_t> failures;
  std::map<std::string, std::pair<std::size_t, std::size_t>> layouts;  // successes, runs
  std::vector<double> ratios;
  for (const nlohmann::json& j : rows) {
    if (!j["feasible"].get<bool>()) {
      ++infeasible;
      continue;
    }
    ++n;
    const bool success = j.value("success", false);
    ok += success;
    const bool can_pass = j.value("passable", true);  // worlds without people: the static route decides
    passable += can_pass;
    passable_ok += can_pass && success;
    if (can_pass && j.contains("contact"))
      (j["contact"]["robot_standing"].get<bool>() ? passable_standing : passable_moving) += 1;
    auto& [lk, ln] = layouts[j["layout"].get<std::string>()];
    lk += success;
    ++ln;
    if (j.contains("error")) {
      ++failures["error"];
      continue;
    }
    if (j.contains("contact")) {
      (j["contact"]["robot_standing"].get<bool>() ? standing : moving) += 1;
      people += j["contact"]["obstacle"].get<std::string>().find('/') != std::string::npos;
    }
    const std::string outcome = j["navigator_outcome"].get<std::string>();
    timeouts += j["timeout"].get<bool>();
    false_success += outcome == "SUCCESS" && !success;
    if (!success) ++failures[outcome == "SUCCESS" ? "SUCCESS (reported, not true)" : outcome];
    if (success && j.value("without_people_success", false))
      ratios.push_back(j["time_s"].get<double>() / std::max(1e-9, j["without_people_time_s"].get<double>()));
  }
  nlohmann::json by_layout = nlohmann::json::object();
  for (const auto& [name, kn] : layouts) by_layout[name] = {{"succeeded", kn.first}, {"runs", kn.second}};
  return {{"robot", robot},
          {"runs", n},
          {"infeasible", infeasible},
          {"success", rate(ok, n)},
          {"contact_moving", rate(moving, n)},
          {"contact_standing", rate(standing, n)},
          {"contacts_with_people", people},
          {"passable", passable},
          {"success_passable", rate(passable_ok, passable)},
          {"contact_moving_passable", rate(passable_moving, passable)},
          {"contact_standing_passable", rate(passable_standing, passable)},
          {"timeout", rate(timeouts, n)},
          {"reported_success_not_true", false_success},
          {"failures", failures},
          {"by_layout", by_layout},
          {"time_vs_without_people_median_ratio",
           ratios.empty() ? nlohmann::json(nullptr) : nlohmann::json(median(ratios))},
          {"time_vs_without_people_runs", ratios.size()}};
}

}  // namespace

nlohmann::json run_world_bench(const WorldBenchOptions& a) {
  require(a.jobs >= 1 && a.jobs <= 64, "--jobs", "in [1, 64]");
  require(!a.robots.empty(), "--robots", "not empty");
  if (!a.cases.empty() && !a.save_worlds.empty())
    throw Error("--save-worlds writes generated worlds; a --cases file's worlds are files already");
  runner::RunOptions base;
  base.params_file = a.params;
  base.stop_on_contact = true;  // a touched run has failed: no need to simulate it to the end
  const std::map<std::string, RobotProfile> profiles = robot_profiles(a.robots, base);
  const std::vector<BenchWorld> worlds = a.cases.empty() ? generated_worlds(a) : case_worlds(a.cases);
  if (!a.save_worlds.empty()) save_worlds(worlds, a.save_worlds);
  std::vector<WorldRun> runs = plan_runs(worlds, a.robots);
  std::map<std::string, RobotProfile> case_profiles = profiles;  // a case's own robot, loaded on demand
  for (const WorldRun& r : runs)
    if (!case_profiles.count(r.robot)) case_profiles[r.robot] = robot_profiles({r.robot}, base).at(r.robot);
  run_in_parallel(runs.size(), a.jobs, "worlds", [&](std::size_t i) {
    run_world(runs[i], worlds[runs[i].world], case_profiles.at(runs[i].robot), base);
  });
  std::map<std::string, std::vector<nlohmann::json>> rows;  // per robot, the runs with people
  nlohmann::json all = nlohmann::json::array();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (runs[i].baseline) continue;
    const WorldRun* baseline = i + 1 < runs.size() && runs[i + 1].baseline ? &runs[i + 1] : nullptr;
    const std::string name = case_profiles.at(runs[i].robot).name;
    rows[name].push_back(run_row(runs[i], worlds[runs[i].world], baseline));
    all.push_back(rows[name].back());
  }
  nlohmann::json report;
  report["title"] = a.cases.empty()
                        ? "bench worlds " + a.family + ": " + std::to_string(a.worlds) + " worlds (seeds " +
                              std::to_string(a.first_seed) + "-" + std::to_string(a.first_seed + a.worlds - 1) + ")"
                        : "bench worlds: " + std::to_string(worlds.size()) + " cases of " + a.cases;
  report["family"] = a.cases.empty() ? a.family : "cases";
  report["first_seed"] = a.first_seed;
  report["worlds"] = worlds.size();
  report["robots"] = nlohmann::json::array();
  for (const auto& [robot, robot_rows] : rows) report["robots"].push_back(robot_summary(robot, robot_rows));
  report["runs"] = all;
  return report;
}

}  // namespace bipednav::bench
