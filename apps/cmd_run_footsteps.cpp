// `bipednav run` with a humanoid robot: footstep navigation instead of velocity commands.
#include "apps/cmd_run_footsteps.hpp"

#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "apps/cli_json.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/footstep_replay.hpp"
#include "bipednav/runner/footstep_runner.hpp"
#include "bipednav/runner/run_json.hpp"

namespace bipednav::app {

bool runs_by_footsteps(const sim::Scenario& scenario, const std::string& robot_override) {
  return runner::is_footstep_robot(navigation::load_robot(robot_override.empty() ? scenario.robot : robot_override));
}

navigation::FootstepNavigatorParams footstep_params_for_cli(const RobotProfile& robot,
                                                            const std::filesystem::path& params_file) {
  try {
    return runner::footstep_navigator_params(robot, params_file);
  } catch (const FileError& e) {
    throw Error(std::string(e.what()) +
                " (a humanoid, kind humanoid, reads the footstep navigator's layout, not a wheeled robot's: "
                "`bipednav params --robot nao` prints it)");
  }
}

namespace {

nlohmann::json footstep_json(const runner::FootstepRunResult& f) {
  const runner::RunResult& r = f.summary;
  std::map<std::string, int> actions;
  for (const auto& s : f.steps) ++actions[s.action];
  nlohmann::json contacts = nlohmann::json::array();
  for (const auto& c : f.contacts)
    contacts.push_back({{"time_s", c.time_s},
                        {"part", c.part},
                        {"x_m", c.point.x()},
                        {"y_m", c.point.y()},
                        {"depth_m", c.penetration_m}});
  nlohmann::json j = runner::run_result_json(r);
  j.update({{"mode", "footsteps"},
            {"contacts", contacts},
            {"steps", f.steps.size()},
            {"actions", actions},
            {"max_body_z_m", f.max_body_z_m},
            {"views", f.views},
            {"gicp_corrections", f.corrections},
            {"recovery_steps", f.recoveries},
            {"rough_landings", f.rough_landings}});
  return j;
}

}  // namespace

bool run_footsteps_command(sim::Scenario scenario, const std::string& robot_override, const std::filesystem::path& out,
                           const FootstepRunArgs& args, const std::filesystem::path& params_file,
                           const std::filesystem::path& replay) {
  if (!robot_override.empty()) scenario.robot = robot_override;
  runner::FootstepRunOptions o;
  o.navigator = footstep_params_for_cli(navigation::load_robot(scenario.robot), params_file);
  if (args.seed) o.seed = *args.seed;
  if (args.time_limit_s) o.time_limit_s = *args.time_limit_s;
  o.progress = args.progress;
  std::unique_ptr<runner::FootstepReplayRecorder> recorder;
  if (!replay.empty()) {
    recorder = std::make_unique<runner::FootstepReplayRecorder>(scenario);
    recorder->attach(o);
  }
  const runner::FootstepRunResult f = runner::run_footstep_scenario(scenario, o);
  nlohmann::json j = footstep_json(f);
  std::ofstream(out / "run.json") << j.dump(2) << "\n";
  runner::write_footstep_figure(out / "run.png", f);
  j["outputs"] = {{"run_json", (out / "run.json").string()}, {"run_png", (out / "run.png").string()}};
  if (recorder) {
    viz::write_replay_html(replay, recorder->finish(f));
    j["outputs"]["replay_html"] = replay.string();
    j["outputs"]["replay_frames"] = recorder->frames().size();
  }
  const runner::RunResult& r = f.summary;
  print_figures(args.json, j, [&] {
    std::printf("%s with %s (footsteps): %s (%s: %s)\n", r.scenario.c_str(), r.robot.c_str(),
                r.success ? "SUCCESS" : "FAILED", std::string(outcome_name(r.outcome.outcome)).c_str(),
                r.outcome.message.c_str());
    std::printf("  %zu steps, %.1f s walked, path %.2f m, collisions %d, min clearance %.3f m\n", f.steps.size(),
                r.time_s, r.path_length_m, r.collisions, r.min_clearance_m);
    std::printf("  goal error %.3f m / %.3f rad, localization error %.3f m, replans %zu, real-time factor %.1fx\n",
                r.goal_error_m, r.goal_error_rad, r.localization_error_m, r.replans, r.real_time_factor);
    std::printf("  wrote %s and %s\n", (out / "run.json").c_str(), (out / "run.png").c_str());
    if (recorder) std::printf("  wrote %s (%zu frames)\n", replay.c_str(), recorder->frames().size());
  });
  return r.success;
}

}  // namespace bipednav::app
