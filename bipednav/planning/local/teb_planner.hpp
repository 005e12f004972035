#pragma once

#include <string_view>
#include <vector>

#include "bipednav/planning/local/body_lag.hpp"
#include "bipednav/planning/local/costmap_obstacles.hpp"
#include "bipednav/planning/local/homotopy.hpp"
#include "bipednav/planning/local/local_planner.hpp"
#include "bipednav/planning/local/plan_utils.hpp"
#include "bipednav/planning/local/teb_params.hpp"

namespace bipednav::planning::local {

// The Timed-Elastic-Band local planner (thesis 5.2) for a walking robot modelled as a
// differential drive. One compute() per control cycle: local goal and via points from the global
// plan, obstacles from the local costmap, homotopy candidates optimised and selected, feasibility
// check, then the first interval's velocity clamped to the limits. With a body response model
// (TebParams::response) the band starts from the body's velocity and the command is the one that
// brings the lagging body to the first interval's velocity (invert_body_lag): the body's target then
// keeps the acceleration limits and the command, within the velocity limits, leads it by more.
class TebPlanner : public LocalPlanner {
 public:
  explicit TebPlanner(TebParams params);

  LocalPlanResult compute(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                          const mapping::Costmap2D& local_costmap, double now_s) override;
  void reset() override;
  std::string_view name() const override { return "teb"; }
  double aimed_xy_goal_tolerance_m() const override { return params_.xy_goal_tolerance_m; }

  const TebParams& params() const { return params_; }
  // The obstacles and candidates of the last compute() (for display and tests).
  const std::vector<Obstacle>& obstacles() const { return obstacles_; }
  const std::vector<BandCandidate>& candidates() const { return homotopy_.candidates(); }
  // The tracker's moving obstacles at now_s for the band (TebOptimizerParams::dynamic_obstacles; empty
  // without it).
  std::vector<TebMovingObstacle> band_moving(double now_s) const;

 private:
  LocalPlanResult plan(const Pose2& T_map_base, const Twist& current_velocity, const Path& global_plan,
                       const mapping::Costmap2D& local_costmap, double now_s);
  LocalPlanResult finish(LocalPlanResult r, const Twist& desired, const Twist& current);
  VelocityLimits command_limits() const;
  bool models_lag() const { return params_.response.time_constant_s > 0.0; }
  BodyLag body_lag() const { return {params_.response.time_constant_s, command_limits()}; }
  // The body's velocity for this cycle from the given one (see TebBodyResponse).
  Twist body_velocity(const Twist& given);

  TebParams params_;
  HomotopyPlanner homotopy_;
  OscillationDetector oscillation_;
  std::vector<Obstacle> obstacles_;
  ObstacleScratch obstacle_scratch_;  // extract_obstacles' buffers, kept between cycles
  bool holding_goal_ = false;         // approach_goal's hysteresis
  Twist last_cmd_;                    // the command of the last compute()
  Twist body_;                        // the body velocity of the last compute() (with the lag model)
};

// The first interval's velocity (eq. 5.8 with the exact sign, eq. 5.9); zero for a degenerate band.
Twist band_command(const TebBand& band);

}  // namespace bipednav::planning::local
