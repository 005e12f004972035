#include "bench/humanoid_drift.hpp"

#include <cmath>

#include "bipednav/common/angles.hpp"
#include "bipednav/common/error.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/footstep_runner.hpp"
#include "bipednav/sim/scenario_files.hpp"

namespace bipednav::bench {

nlohmann::json bench_humanoid_drift(const HumanoidDriftOptions& options) {
  // The reference's Nao under motion capture over 3.47 m: 0.21 m and 3.46 deg accumulated by the
  // corrected estimate, 0.53 m and 6.10 deg by the leg odometry.
  constexpr double kRefCorrectedCmPerM = 5.9, kRefCorrectedDegPerM = 0.99;
  constexpr double kRefOdometryCmPerM = 15.3, kRefOdometryDegPerM = 1.76;
  const sim::Scenario scenario = sim::load_scenario(sim::resolve_scenario(options.scenario));
  runner::FootstepRunOptions o;
  o.navigator = runner::footstep_navigator_params(navigation::load_robot(scenario.robot), {});
  const runner::FootstepRunResult run = runner::run_footstep_scenario(scenario, o);
  if (run.steps.empty()) throw Error("bench localization: the humanoid took no step in " + scenario.name);
  const runner::ExecutedStep& last = run.steps.back();
  const double path_m = run.summary.path_length_m;
  // Accumulated drift per metre walked, as the reference computes it: the error at the end over the
  // distance travelled.
  const auto cm_per_m = [&](const Pose2& estimate) { return 100.0 * distance(estimate, last.body) / path_m; };
  const auto deg_per_m = [&](const Pose2& estimate) {
    return rad2deg(std::abs(angle_diff(estimate.theta, last.body.theta))) / path_m;
  };
  const double corrected_cm = cm_per_m(last.estimated_body), odometry_cm = cm_per_m(last.odometry_body);
  return {{"humanoid_scenario", scenario.name},
          {"humanoid_outcome", std::string(outcome_name(run.summary.outcome.outcome))},
          {"humanoid_steps", run.steps.size()},
          {"humanoid_path_m", path_m},
          {"humanoid_corrected_cm_per_m", corrected_cm},
          {"humanoid_corrected_deg_per_m", deg_per_m(last.estimated_body)},
          {"humanoid_odometry_cm_per_m", odometry_cm},
          {"humanoid_odometry_deg_per_m", deg_per_m(last.odometry_body)},
          {"humanoid_corrected_vs_odometry_ratio", odometry_cm > 0.0 ? corrected_cm / odometry_cm : 0.0},
          {"goal_humanoid_corrected_vs_odometry_ratio", 1.0 / 3.0},
          {"meets_goal_humanoid_corrected_vs_odometry", corrected_cm < odometry_cm / 3.0},
          {"reference_corrected_cm_per_m", kRefCorrectedCmPerM},
          {"reference_corrected_deg_per_m", kRefCorrectedDegPerM},
          {"reference_odometry_cm_per_m", kRefOdometryCmPerM},
          {"reference_odometry_deg_per_m", kRefOdometryDegPerM}};
}

}  // namespace bipednav::bench
