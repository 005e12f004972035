#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/angles.hpp"
#include "bipednav/navigation/footstep_navigator.hpp"
#include "bipednav/runner/scenario_runner.hpp"
#include "bipednav/sim/depth_camera.hpp"
#include "bipednav/sim/humanoid_walker.hpp"

namespace bipednav::runner {

struct FootstepRunOptions {
  std::optional<std::uint64_t> seed;   // overrides the scenario's seed
  std::optional<double> time_limit_s;  // overrides the scenario's time limit (simulated seconds)
  std::filesystem::path config_dir;    // robot profiles (empty: the compiled-in config/)
  navigation::FootstepNavigatorParams navigator;
  sim::HumanoidWalkerParams walker;  // its body is replaced by the planner's body model
  sim::DepthCameraParams camera;
  double head_yaw_rad = deg2rad(17.0);  // two views, at +head_yaw_rad and -head_yaw_rad
  int steps_per_view = 2;               // views every second step (section VI)
  // Before the first step the robot looks around: extra views at these head yaws (Nao's head
  // turns +-119 deg), so the first plan knows the sides and not only the front.
  std::vector<double> initial_head_yaws_rad = {-1.9, -1.0, 1.0, 1.9};
  double truth_resolution_m = 0.005;  // the true terrain's heightmap
  double map_resolution_m = 0.01;     // the navigator's heightmap
  double map_margin_m = 0.0;          // around the scenario's bounds
  bool progress = false;
  // Called at every step decision (after the head views and the plan, before the step is walked),
  // the final one included; the HTML replay records through it (footstep_replay.hpp).
  std::function<void(const sim::HumanoidWalker&, const navigation::FootstepNavigator&, const navigation::StepDecision&)>
      on_decision;

  void validate() const;
};

// One executed step (ground truth, and the navigator's estimate of the body).
struct ExecutedStep {
  double t_s = 0.0;
  planning::footstep::Footstep foot;  // where the swing foot really landed
  std::string action;
  Pose2 body, estimated_body;
  Pose2 odometry_body;    // the body from the leg odometry alone (its frame is the world at the start)
  double body_z_m = 0.0;  // the stance sole's height after the step
  bool replanned = false;
};

struct FootstepRunResult {
  RunResult summary;  // the fields shared with the wheeled runs (no snapshots)
  std::vector<planning::footstep::Footstep> start_feet;
  std::vector<ExecutedStep> steps;
  planning::footstep::FootstepPlan first_plan, last_plan;
  std::vector<sim::BodyContact> contacts;  // ground-truth whole-body collisions
  Twist first_contact_velocity;            // the body's mean velocity over the step of the first contact
  mapping::Heightmap map;                  // the navigator's heightmap at the end
  planning::footstep::BodyModel body;
  Pose2 start, goal;
  double max_body_z_m = 0.0;
  std::size_t views = 0, corrections = 0;
  std::size_t recoveries = 0;      // corrective steps after a failed plan (footstep_navigator.hpp)
  std::size_t rough_landings = 0;  // true terrain under a landed sole spread over the flatness threshold
};

// Whether a robot profile navigates by footsteps (kind: humanoid).
bool is_footstep_robot(const RobotProfile& robot);
// The footstep navigator's parameters for a run of `robot`: its defaults, the robot's tuning
// (config/<name>.params.yaml; planner.robot picks the action set), then the navigation parameters
// file `params_file` in the footstep layout (navigation::footstep_navigator_params_for; empty: none).
navigation::FootstepNavigatorParams footstep_navigator_params(const RobotProfile& robot,
                                                              const std::filesystem::path& params_file);

// The humanoid closed loop: head depth views (two, every second step) -> GICP-corrected kinematic
// odometry -> Kalman heightmap -> ARA* footsteps (replanned when invalid) -> the walker executes
// each step relative to its stance foot on the true terrain with a whole-body collision check.
// Success (judge_run) = the navigator reached the goal, the true body is within the scenario's
// tolerances and no body part collided.
FootstepRunResult run_footstep_scenario(const sim::Scenario& scenario, const FootstepRunOptions& options);

// The navigator's heightmap with the last plan (faint), the executed feet, the robot, the start and
// the goal, with a legend, a scale bar and the heights' grey ramp.
void write_footstep_figure(const std::filesystem::path& file, const FootstepRunResult& run);

}  // namespace bipednav::runner
