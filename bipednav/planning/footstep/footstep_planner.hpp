#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bipednav/common/outcome.hpp"
#include "bipednav/mapping/heightmap.hpp"
#include "bipednav/planning/footstep/ara_star.hpp"
#include "bipednav/planning/footstep/footstep_graph.hpp"

namespace bipednav::planning::footstep {

struct FootstepPlannerParams {
  std::string robot = "nao";           // action set: nao | digit
  bool planar_only = false;            // the 2D baseline: planar footsteps only
  double lattice_resolution_m = 0.01;  // x/y discretisation of states
  int theta_bins = 32;                 // 11.25 deg, finer than the smallest turning step
  std::string heuristic = "dijkstra";  // dijkstra | euclidean
  double goal_tolerance_m = 0.05;
  double goal_tolerance_rad = 0.3;
  // A landed sole keeps this far from rising edges (footstep_graph.hpp): the walker's landing
  // error. 0 (Table I, exact footholds); the closed loop sets it (footstep_navigator.hpp).
  double landing_margin_m = 0.0;
  // > 0: the torso and arms keep off unknown cells behind a face rising more than this above its
  // known neighbours (TerrainGrid::occluded), which the head camera may see only the lower part
  // of. 0 (off): unknown cells are free to every body part.
  double occlusion_rise_m = 0.0;
  AraStarParams search;  // initial epsilon 8, decreasing to 1 within the time limit

  void validate() const;

  // The fields a navigation parameters file reads and `bipednav params` prints, in this order
  // (navigation/navigator_params_yaml.hpp).
  template <class V>
  void visit_fields(V& v) {
    v("robot", robot);
    v("planar_only", planar_only);
    v("lattice_resolution_m", lattice_resolution_m);
    v("theta_bins", theta_bins);
    v("heuristic", heuristic);
    v("goal_tolerance_m", goal_tolerance_m);
    v("goal_tolerance_rad", goal_tolerance_rad);
    v("landing_margin_m", landing_margin_m);
    v("occlusion_rise_m", occlusion_rise_m);
    v.group("search", search);
  }
};

struct FootstepPlan {
  Result result;
  std::vector<Footstep> steps;       // the start stance foot first, then every landed foot
  std::vector<std::string> actions;  // actions[i] moves from steps[i] to steps[i + 1]
  double cost_s = 0.0;               // travel time
  double setup_s = 0.0;              // terrain pooling and heuristic before the search
  double first_solution_s = 0.0;     // search time to the first solution (search.clock, as all times)
  double first_solution_cost_s = 0.0;
  double final_epsilon = 0.0;  // proven suboptimality bound of `cost_s`
  std::size_t expansions = 0;
  double time_s = 0.0;
  std::vector<AnytimeIteration> iterations;
};

// ARA* footstep planning on a heightmap with whole-body checks (the second reference).
// The action lattice (transitions, inverse heightmaps) is built once in the constructor.
class FootstepPlanner {
 public:
  explicit FootstepPlanner(FootstepPlannerParams params);

  // Plans from a start stance foot to a goal body pose. Outcomes: SUCCESS, PLAN_OUT_OF_MAP,
  // BLOCKED_GOAL (no safe stance exists at the goal), NO_PATH_FOUND, PLAN_PAT_EXCEEDED.
  // `swing_z_m`: the height of the other (swing) foot where it stands, when known. Standing
  // higher than the start foot (mid-way down a step), it keeps that height until it drops onto
  // its landing, and the first step's whole-body check follows it (FootstepGraph); without it
  // or at the stance height the swing foot is taken at the stance height.
  FootstepPlan plan(const mapping::Heightmap& map, const Footstep& start, const Pose2& goal,
                    std::optional<double> swing_z_m = std::nullopt) const;
  // Whether every step of `plan` is still safe on `map` (replan when it is not); `swing_z_m`:
  // the swing foot's height beside plan.steps.front(), as in plan().
  bool still_valid(const mapping::Heightmap& map, const FootstepPlan& plan,
                   std::optional<double> swing_z_m = std::nullopt) const;
  // The actions that are safe from `from` on `map` (flat landing, dz, whole body), each with
  // the foot it lands (on the lattice). For recovery steps when no plan reaches the goal.
  std::vector<std::pair<std::string, Footstep>> safe_steps(const mapping::Heightmap& map, const Footstep& from,
                                                           std::optional<double> swing_z_m = std::nullopt) const;

  // The stance foot pose for a body pose (feet half a separation to each side).
  Footstep stance_for_body(const Pose2& body, Foot foot, double z_m = 0.0) const;
  const FootstepPlannerParams& params() const { return params_; }
  const ActionLattice& lattice() const { return *lattice_; }

 private:
  FootstepPlannerParams params_;
  std::unique_ptr<ActionLattice> lattice_;
};

}  // namespace bipednav::planning::footstep
