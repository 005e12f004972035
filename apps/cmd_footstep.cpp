// `bipednav footsteps` (plan on a heightmap image and draw the plan) and `bench footsteps`
// (the second reference's Table I on random cluttered heightmaps).
#include <cstdio>
#include <memory>
#include <string>

#include "apps/bench_footsteps.hpp"
#include "apps/cli_checks.hpp"
#include "apps/cli_exit.hpp"
#include "apps/cli_json.hpp"
#include "apps/cli_output.hpp"
#include "apps/cli_pose.hpp"
#include "apps/commands.hpp"
#include "bipednav/mapping/map_io.hpp"
#include "bipednav/planning/footstep/footstep_planner.hpp"
#include "bipednav/runner/footstep_drawing.hpp"
#include "bipednav/viz/canvas.hpp"

namespace bipednav::app {

namespace {

using namespace planning::footstep;

// The heightmap with the planned feet on top (runner/footstep_drawing.hpp).
void draw_plan(const std::filesystem::path& file, const mapping::Heightmap& map, const FootstepPlanner& planner,
               const FootstepPlan& plan, const Pose2& start, const Pose2& goal) {
  viz::Canvas c(runner::footstep_canvas(map.geometry(), false));
  const runner::HeightRange heights = runner::draw_heightmap(c, map);
  runner::draw_footsteps(c, planner.lattice().actions().body, plan.steps, plan.actions);
  runner::draw_start(c, start);
  runner::draw_goal(c, goal);
  const std::string title = std::string(outcome_name(plan.result.outcome)) + ": " +
                            (plan.result.ok() ? std::to_string(plan.actions.size()) + " steps" : plan.result.message);
  runner::draw_footstep_legend(c, title, heights, false);
  c.write_png(file);
}

struct FootstepArgs {
  std::string heightmap, start, goal, out = "footsteps.png", robot = "nao", heuristic = "dijkstra";
  double resolution_m = 0.02, min_height_m = -0.5, max_height_m = 1.0, time_limit_s = 5.0;
  bool json = false;
};

// The plan's figures (a failed plan: outcome and message only, the rest null).
nlohmann::json plan_json(const FootstepPlan& plan, const std::string& out) {
  const bool ok = plan.result.ok();
  const auto when_ok = [ok](auto v) { return ok ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"outcome", std::string(outcome_name(plan.result.outcome))},
          {"outcome_code", code(plan.result.outcome)},
          {"message", plan.result.message},
          {"steps", when_ok(plan.actions.size())},
          {"walking_s", when_ok(plan.cost_s)},
          {"final_epsilon", when_ok(plan.final_epsilon)},
          {"first_solution_s", when_ok(plan.first_solution_s)},
          {"expansions", plan.expansions},
          {"png", out}};
}

// Returns whether a plan was found (the exit status).
bool footsteps_command(const FootstepArgs& a) {
  const Pose2 start = parse_pose(a.start, "--start"), goal = parse_pose(a.goal, "--goal");
  prepare_output_file(a.out, "--out");
  mapping::Heightmap map;
  with_flag_names(
      {{"resolution_m", "--resolution"}, {"min_height_m", "--min-height"}, {"max_height_m", "--max-height"}}, [&] {
        map = mapping::read_heightmap_image(a.heightmap, {a.resolution_m, a.min_height_m, a.max_height_m, 0.0, 0.0});
      });
  FootstepPlannerParams p;
  p.robot = a.robot;
  p.heuristic = a.heuristic;
  p.search.time_limit_s = a.time_limit_s;
  const FootstepPlanner planner(p);
  const FootstepPlan plan = planner.plan(map, planner.stance_for_body(start, Foot::kLeft), goal);
  draw_plan(a.out, map, planner, plan, start, goal);
  print_figures(a.json, plan_json(plan, a.out), [&] {
    std::printf("%s: %s\n", std::string(outcome_name(plan.result.outcome)).c_str(), plan.result.message.c_str());
    if (plan.result.ok()) {
      std::printf("  %zu steps, %.2f s of walking, bound eps %.2f, first solution after %.3f s, %zu expansions\n",
                  plan.actions.size(), plan.cost_s, plan.final_epsilon, plan.first_solution_s, plan.expansions);
    }
    std::printf("  wrote %s\n", a.out.c_str());
  });
  return plan.result.ok();
}

}  // namespace

void add_footstep_commands(CLI::App& app, CLI::App& bench) {
  auto a = std::make_shared<FootstepArgs>();
  CLI::App* fs = app.add_subcommand("footsteps", "Plan footsteps on a heightmap image and draw them");
  fs->add_option("heightmap", a->heightmap, "Heightmap PNG, or a YAML with image/resolution_m/min/max_height_m")
      ->required()
      ->check(CLI::ExistingFile);
  fs->add_option("--start", a->start, "Start body pose x,y[,yaw]")->required();
  fs->add_option("--goal", a->goal, "Goal body pose x,y[,yaw]")->required();
  fs->add_option("--out", a->out, "Output PNG")->capture_default_str();
  fs->add_option("--robot", a->robot, "nao or digit")->capture_default_str()->check(CLI::IsMember({"nao", "digit"}));
  fs->add_option("--heuristic", a->heuristic, "dijkstra or euclidean")
      ->capture_default_str()
      ->check(CLI::IsMember({"dijkstra", "euclidean"}));
  fs->add_option("--resolution", a->resolution_m, "PNG: metres per pixel")
      ->capture_default_str()
      ->check(check::positive());
  fs->add_option("--min-height", a->min_height_m, "PNG: height of grey 0, m")
      ->capture_default_str()
      ->check(check::finite());
  fs->add_option("--max-height", a->max_height_m, "PNG: height of grey 255, m")
      ->capture_default_str()
      ->check(check::finite());
  fs->add_option("--time-limit", a->time_limit_s, "ARA* time limit, s")
      ->capture_default_str()
      ->check(check::positive());
  add_json_flag(fs, a->json);
  fs->callback([a] { report_task(footsteps_command(*a)); });

  add_footstep_bench(bench);
}

}  // namespace bipednav::app
