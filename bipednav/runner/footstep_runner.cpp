#include "bipednav/runner/footstep_runner.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "bipednav/common/clock.hpp"
#include "bipednav/common/progress.hpp"
#include "bipednav/navigation/navigator_params_yaml.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/footstep_drawing.hpp"
#include "bipednav/sim/raycaster.hpp"
#include "bipednav/sim/terrain_truth.hpp"

namespace bipednav::runner {

void FootstepRunOptions::validate() const {
  navigator.validate();
  walker.validate();
  camera.validate();
  require(std::isfinite(head_yaw_rad) && std::abs(head_yaw_rad) < 1.5, "head_yaw_rad", "in (-1.5, 1.5) rad");
  require(steps_per_view >= 1, "steps_per_view", ">= 1");
  for (double y : initial_head_yaws_rad)
    require(std::isfinite(y) && std::abs(y) <= 2.1, "initial_head_yaws_rad", "in [-2.1, 2.1] rad");
  require(truth_resolution_m > 0.0 && truth_resolution_m <= 0.05, "truth_resolution_m", "in (0, 0.05] m");
  require(map_resolution_m > 0.0 && map_resolution_m <= 0.1, "map_resolution_m", "in (0, 0.1] m");
  require(map_margin_m >= 0.0, "map_margin_m", ">= 0");
  if (time_limit_s) require(*time_limit_s > 0.0, "time_limit_s", "> 0");
}

bool is_footstep_robot(const RobotProfile& robot) { return robot.kind == "humanoid"; }

navigation::FootstepNavigatorParams footstep_navigator_params(const RobotProfile& robot,
                                                              const std::filesystem::path& params_file) {
  return navigation::footstep_navigator_params_for(robot, params_file);
}

namespace {

// Everything that exists only during a run.
struct Loop {
  const sim::Scenario& scenario;
  const FootstepRunOptions& o;
  SE3 T_base_camera;
  sim::RayCaster caster;
  mapping::Heightmap truth;
  navigation::FootstepNavigator nav;
  sim::HumanoidWalker walker;
  sim::DepthCamera camera;
  FootstepRunResult out;

  Loop(const sim::Scenario& s, const FootstepRunOptions& opt, const SensorMount& mount, std::uint64_t seed)
      : scenario(s),
        o(opt),
        T_base_camera(mount.T_base_sensor()),
        caster(s.world),
        truth(sim::true_heightmap(caster, global_geometry_for(s, opt.truth_resolution_m, opt.map_margin_m), 5.0)),
        nav(opt.navigator, global_geometry_for(s, opt.map_resolution_m, opt.map_margin_m)),
        walker(walker_params(opt, nav), truth, s.start, seed),
        camera(opt.camera, mount.name, seed + 1) {}

  static sim::HumanoidWalkerParams walker_params(const FootstepRunOptions& opt,
                                                 const navigation::FootstepNavigator& n) {
    sim::HumanoidWalkerParams p = opt.walker;
    p.body = n.planner().lattice().actions().body;
    return p;
  }

  // Two head views (+yaw, -yaw) from where the robot stands, into the navigator.
  void look() {
    std::vector<double> yaws = {o.head_yaw_rad, -o.head_yaw_rad};
    if (out.views == 0) yaws.insert(yaws.end(), o.initial_head_yaws_rad.begin(), o.initial_head_yaws_rad.end());
    std::vector<navigation::DepthView> views;
    for (double yaw : yaws) {
      const SE3 T_base_camera_yawed = make_se3(0, 0, 0, 0, 0, yaw) * T_base_camera;
      views.push_back({camera.capture_at(walker.time_s(), walker.T_world_base() * T_base_camera_yawed, caster),
                       T_base_camera_yawed});
      ++out.views;
    }
    nav.observe(views, walker.T_odom_base());
  }

  void record(const sim::StepExecution& e, const planning::footstep::FootstepAction& a, bool replanned) {
    const Pose2 before = out.steps.empty() ? scenario.start : out.steps.back().body;
    const planning::footstep::Footstep est = nav.to_map(walker.odom_stance()),
                                       est_other = nav.to_map(walker.odom_swing());
    ExecutedStep s{walker.time_s(),
                   e.landed,
                   a.name,
                   walker.body_pose(),
                   sim::body_between(est.pose, est_other.pose),
                   pose2_from_se3(walker.T_odom_base()),
                   walker.stance().z_m,
                   replanned};
    out.summary.path_length_m += distance(before, s.body);
    out.summary.min_clearance_m = std::min(out.summary.min_clearance_m, e.min_clearance_m);
    out.max_body_z_m = std::max(out.max_body_z_m, s.body_z_m);
    out.rough_landings += e.landing_spread_m > nav.planner().lattice().actions().flatness_threshold_m;
    if (out.contacts.empty() && !e.contacts.empty()) {
      // Contacts happen while a foot swings: the body moves over the step.
      const double dt = walker.time_s() - (out.steps.empty() ? 0.0 : out.steps.back().t_s);
      if (dt > 0.0)
        out.first_contact_velocity =
            Twist{distance(before, s.body) / dt, 0.0, angle_diff(s.body.theta, before.theta) / dt};
    }
    out.contacts.insert(out.contacts.end(), e.contacts.begin(), e.contacts.end());
    out.summary.trace.push_back({s.t_s, s.body, s.estimated_body, {}, a.name, {}});
    out.steps.push_back(std::move(s));
  }

  // Footstep runs navigate to the scenario's last goal (intermediate timed goals are not used).
  Result run(double time_limit_s) {
    nav.set_goal(scenario.goals.back().pose);
    out.summary.goals_given = 1;
    ProgressBar bar("footsteps " + scenario.name, static_cast<std::size_t>(time_limit_s), o.progress);
    for (std::size_t i = 0; walker.time_s() < time_limit_s; ++i) {
      if (i % static_cast<std::size_t>(o.steps_per_view) == 0) look();
      const navigation::StepDecision d = nav.next(walker.odom_stance(), walker.odom_swing());
      if (d.replanned && nav.plan().result.ok())
        (out.first_plan.steps.empty() ? out.first_plan : out.last_plan) = nav.plan();
      if (o.on_decision) o.on_decision(walker, nav, d);
      if (d.done) {
        bar.finish();
        return d.result;
      }
      const planning::footstep::Footstep stance = nav.to_map(walker.odom_stance());
      const sim::StepExecution e =
          walker.step({stance.pose.inverse() * d.target.pose, d.action->duration_s, d.action->peak_m, d.action->name});
      record(e, *d.action, d.replanned);
      for (const sim::BodyContact& c : e.contacts)  // a sole on an edge: the robot falls
        if (c.part == "landing_foot") {
          bar.finish();
          return {Outcome::COLLISION, "the foot came down on an edge (fall)"};
        }
      bar.update(static_cast<std::size_t>(walker.time_s()));
    }
    bar.finish();
    return {Outcome::CTRL_PAT_EXCEEDED, "time limit reached before the goal"};
  }
};

}  // namespace

FootstepRunResult run_footstep_scenario(const sim::Scenario& scenario, const FootstepRunOptions& options) {
  options.validate();
  scenario.validate();
  if (scenario.goals.empty()) throw Error("scenario '" + scenario.name + "' has no goal");
  const RobotProfile robot = navigation::load_robot(scenario.robot, options.config_dir);
  if (!is_footstep_robot(robot)) throw Error("robot '" + robot.name + "' does not walk by footsteps");
  const SensorMount* mount = robot.sensor("depth_head");
  if (!mount) throw Error("robot '" + robot.name + "' has no depth_head camera");
  const Stopwatch wall;
  Loop loop(scenario, options, *mount, options.seed.value_or(scenario.seed));
  FootstepRunResult& out = loop.out;
  out.summary.scenario = scenario.name;
  out.summary.robot = robot.name;
  out.summary.min_clearance_m = std::numeric_limits<double>::infinity();
  out.start_feet = {loop.walker.stance(), loop.walker.swing()};
  out.body = loop.nav.planner().lattice().actions().body;
  out.goal = scenario.goals.back().pose;
  out.start = scenario.start;
  out.summary.outcome = loop.run(options.time_limit_s.value_or(scenario.time_limit_s));
  if (out.last_plan.steps.empty()) out.last_plan = out.first_plan;
  out.map = loop.nav.map();
  out.corrections = loop.nav.corrections();
  out.recoveries = loop.nav.recoveries();
  RunResult& r = out.summary;
  r.wall_s = wall.elapsed_ms() / 1000.0;
  r.time_s = loop.walker.time_s();
  r.real_time_factor = r.wall_s > 0 ? r.time_s / r.wall_s : 0.0;
  r.collisions = static_cast<int>(out.contacts.size());
  if (!out.contacts.empty()) {
    const sim::BodyContact& c = out.contacts.front();
    r.first_collision = sim::CollisionEvent{c.time_s, loop.walker.body_pose(), c.point,
                                            c.part,   c.penetration_m,         out.first_contact_velocity};
  }
  r.replans = loop.nav.plans() > 0 ? loop.nav.plans() - 1 : 0;
  const Pose2 body = loop.walker.body_pose();
  const planning::footstep::Footstep est = loop.nav.to_map(loop.walker.odom_stance());
  r.localization_error_m = distance(sim::body_between(est.pose, loop.nav.to_map(loop.walker.odom_swing()).pose), body);
  r.goal_error_m = distance(out.goal, body);
  r.goal_error_rad = std::abs(angle_diff(out.goal.theta, body.theta));
  r.seed = options.seed.value_or(scenario.seed);
  r.final_true_pose = body;
  r.final_estimated_pose = sim::body_between(est.pose, loop.nav.to_map(loop.walker.odom_swing()).pose);
  judge_run(r, scenario.goal_tolerance_m, scenario.goal_tolerance_rad);
  return out;
}

void write_footstep_figure(const std::filesystem::path& file, const FootstepRunResult& run) {
  viz::Canvas c(footstep_canvas(run.map.geometry(), true));
  const HeightRange heights = draw_heightmap(c, run.map);
  draw_footsteps(c, run.body, run.last_plan.steps, run.last_plan.actions, 0.08, 0.7);
  std::vector<planning::footstep::Footstep> feet = run.start_feet;
  std::vector<std::string> actions = {""};
  for (const auto& s : run.steps) feet.push_back(s.foot), actions.push_back(s.action);
  draw_footsteps(c, run.body, feet, actions);
  std::vector<Eigen::Vector2d> path;
  for (const auto& s : run.steps) path.push_back(s.body.position());
  if (path.size() > 1) c.polyline(path, viz::colors::kPurple, 1.5);
  for (const auto& k : run.contacts) c.circle(k.point, 0.03, viz::colors::kNone, viz::colors::kRed, 3.0);
  draw_start(c, run.start);
  draw_goal(c, run.goal);
  if (!run.steps.empty()) c.arrow(run.steps.back().body, 0.2, viz::colors::kBlack, 3.0);
  const auto& r = run.summary;
  char title[256];
  std::snprintf(title, sizeof title, "%s: %s, %zu steps, %.1f s, %zu replans, %d collisions", r.scenario.c_str(),
                std::string(outcome_name(r.outcome.outcome)).c_str(), run.steps.size(), r.time_s, r.replans,
                r.collisions);
  draw_footstep_legend(c, title, heights, true);
  c.write_png(file);
}

}  // namespace bipednav::runner
