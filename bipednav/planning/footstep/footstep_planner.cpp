#include "bipednav/planning/footstep/footstep_planner.hpp"

#include <cmath>

namespace bipednav::planning::footstep {

void FootstepPlannerParams::validate() const {
  require(robot == "nao" || robot == "digit", "robot", "nao or digit");
  require(lattice_resolution_m > 0.0 && lattice_resolution_m <= 0.1, "lattice_resolution_m", "in (0, 0.1] m");
  require(theta_bins >= 8 && theta_bins <= 360, "theta_bins", "in [8, 360]");
  require(heuristic == "dijkstra" || heuristic == "euclidean", "heuristic", "dijkstra or euclidean");
  require(goal_tolerance_m > 0.0, "goal_tolerance_m", "> 0");
  require(goal_tolerance_rad > 0.0, "goal_tolerance_rad", "> 0");
  require(std::isfinite(occlusion_rise_m) && occlusion_rise_m >= 0.0, "occlusion_rise_m", ">= 0 m (0: off)");
  require(std::isfinite(landing_margin_m) && landing_margin_m >= 0.0 && landing_margin_m <= 0.1, "landing_margin_m",
          "in [0, 0.1] m");
  search.validate();
}

FootstepPlanner::FootstepPlanner(FootstepPlannerParams params) : params_(std::move(params)) {
  params_.validate();
  ActionSet set = action_set_for(params_.robot);
  if (params_.planar_only) set = planar_only(set);
  lattice_ =
      std::make_unique<ActionLattice>(set, params_.lattice_resolution_m, params_.theta_bins, params_.landing_margin_m);
}

Footstep FootstepPlanner::stance_for_body(const Pose2& body, Foot foot, double z_m) const {
  const double half = lattice_->actions().body.nominal_separation_m / 2.0;
  return {body * Pose2{0.0, foot == Foot::kLeft ? half : -half, 0.0}, z_m, foot};
}

namespace {

std::unique_ptr<Heuristic> make_heuristic(const FootstepPlannerParams& p, const TerrainGrid& t, const ActionSet& a,
                                          const Pose2& goal) {
  if (p.heuristic == "euclidean")
    return std::make_unique<EuclideanHeuristic>(goal, p.goal_tolerance_m, a.fastest_speed_mps());
  return std::make_unique<DijkstraHeuristic>(t, a, goal, p.goal_tolerance_m);
}

// Whether a safe stance exists at the goal for either foot (else BLOCKED_GOAL).
bool goal_standable(const TerrainGrid& t, const ActionSet& a, const FootstepPlanner& planner, const Pose2& goal) {
  for (Foot f : {Foot::kLeft, Foot::kRight}) {
    const Footstep s = planner.stance_for_body(goal, f);
    const auto c = t.geometry().world_to_cell(s.pose.x, s.pose.y);
    if (!c) continue;
    float lo = 1e9f, hi = -1e9f;
    for (const auto& [dx, dy] : planner.lattice().sole(planner.lattice().bin_of(s.pose.theta))) {
      if (!t.in_bounds(c->x + dx, c->y + dy) || !t.known(c->x + dx, c->y + dy)) continue;
      lo = std::min(lo, t.min_h(c->x + dx, c->y + dy));
      hi = std::max(hi, t.max_h(c->x + dx, c->y + dy));
    }
    if (hi < lo || hi - lo <= a.flatness_threshold_m) return true;
  }
  return false;
}

// How much higher than `stance` the swing foot stands (FootstepGraph's start_swing_lift_m).
double swing_lift_m(const Footstep& stance, std::optional<double> swing_z_m) {
  return swing_z_m && std::isfinite(*swing_z_m) ? *swing_z_m - stance.z_m : 0.0;
}

}  // namespace

FootstepPlan FootstepPlanner::plan(const mapping::Heightmap& map, const Footstep& start, const Pose2& goal,
                                   std::optional<double> swing_z_m) const {
  FootstepPlan out;
  if (!start.pose.is_finite() || !goal.is_finite()) {
    out.result = {Outcome::INVALID_GOAL, "start or goal is not finite"};
    return out;
  }
  const SearchClock setup_clock(params_.search.clock);
  const TerrainGrid terrain(map, params_.lattice_resolution_m, params_.occlusion_rise_m);
  const auto& g = terrain.geometry();
  if (!g.world_to_cell(start.pose.x, start.pose.y)) {
    out.result = {Outcome::PLAN_OUT_OF_MAP, "start foot is outside the heightmap"};
    return out;
  }
  if (!g.world_to_cell(goal.x, goal.y)) {
    out.result = {Outcome::PLAN_OUT_OF_MAP, "goal is outside the heightmap"};
    return out;
  }
  const ActionSet& actions = lattice_->actions();
  if (!goal_standable(terrain, actions, *this, goal)) {
    out.result = {Outcome::BLOCKED_GOAL, "no flat stance for either foot at the goal"};
    return out;
  }
  const auto heuristic = make_heuristic(params_, terrain, actions, goal);
  FootstepGraph graph(*lattice_, terrain, *heuristic, {goal, params_.goal_tolerance_m, params_.goal_tolerance_rad},
                      start, swing_lift_m(start, swing_z_m));
  out.setup_s = setup_clock.elapsed_s();
  const AraStarResult r = ara_star(graph, params_.search);
  out.expansions = r.expansions;
  out.time_s = r.time_s;
  out.iterations = r.iterations;
  if (!r.found) {
    out.result = r.time_exceeded ? Result{Outcome::PLAN_PAT_EXCEEDED, "no footstep plan within the time limit"}
                                 : Result{Outcome::NO_PATH_FOUND, "no safe footstep sequence reaches the goal"};
    return out;
  }
  for (auto s : r.states) out.steps.push_back(graph.footstep(s));
  for (auto a : r.actions) out.actions.push_back(actions.actions[a].name);
  out.cost_s = r.cost;
  out.final_epsilon = r.final_epsilon;
  out.first_solution_s = r.iterations.front().time_s;
  out.first_solution_cost_s = r.iterations.front().cost;
  out.result = {Outcome::SUCCESS, "footstep plan with " + std::to_string(out.actions.size()) + " steps"};
  return out;
}

bool FootstepPlanner::still_valid(const mapping::Heightmap& map, const FootstepPlan& plan,
                                  std::optional<double> swing_z_m) const {
  if (plan.steps.size() < 2) return !plan.steps.empty();
  const TerrainGrid terrain(map, params_.lattice_resolution_m, params_.occlusion_rise_m);
  const EuclideanHeuristic none(plan.steps.back().pose, 1.0, 1.0);
  FootstepGraph graph(*lattice_, terrain, none, {plan.steps.back().pose, 1.0, 1.0}, plan.steps.front(),
                      swing_lift_m(plan.steps.front(), swing_z_m));
  std::int32_t s = graph.start_state();
  for (const std::string& name : plan.actions) {
    int a = -1;
    for (std::size_t i = 0; i < lattice_->actions().actions.size(); ++i)
      if (lattice_->actions().actions[i].name == name) a = static_cast<int>(i);
    std::int32_t next = -1;
    if (a < 0 || !graph.action_safe(s, a, &next)) return false;
    s = next;
  }
  return true;
}

std::vector<std::pair<std::string, Footstep>> FootstepPlanner::safe_steps(const mapping::Heightmap& map,
                                                                          const Footstep& from,
                                                                          std::optional<double> swing_z_m) const {
  std::vector<std::pair<std::string, Footstep>> out;
  if (!from.pose.is_finite() || !std::isfinite(from.z_m)) return out;
  const TerrainGrid terrain(map, params_.lattice_resolution_m, params_.occlusion_rise_m);
  if (!terrain.geometry().world_to_cell(from.pose.x, from.pose.y)) return out;
  const EuclideanHeuristic none(from.pose, 1.0, 1.0);
  FootstepGraph graph(*lattice_, terrain, none, {from.pose, 1.0, 1.0}, from, swing_lift_m(from, swing_z_m));
  const auto& actions = lattice_->actions().actions;
  for (std::size_t a = 0; a < actions.size(); ++a) {
    std::int32_t to = -1;
    if (graph.action_safe(graph.start_state(), static_cast<int>(a), &to))
      out.emplace_back(actions[a].name, graph.footstep(to));
  }
  return out;
}

}  // namespace bipednav::planning::footstep
